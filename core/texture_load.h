#pragma once
// Decoding textures (PNG, JPEG, EXR, ...) through the OpenImageIO plugin, loaded on first use
// so that scenes without textures never map OpenImageIO's libraries.
#include <memory>
#include <string>
#include <vector>

#include "core/texture.h"

namespace sl {

// Throws InputError "<name>: why" when the image cannot be read. `srgb` decodes 8/16-bit
// values from sRGB to linear (float formats are linear already).
std::shared_ptr<TextureImage> load_texture_file(const std::string& path, bool srgb);
// The same from encoded bytes in memory (an image inside a .glb or a data: URI).
std::shared_ptr<TextureImage> load_texture_memory(const std::vector<unsigned char>& bytes, const std::string& name,
                                                  const std::string& format_hint, bool srgb);

}  // namespace sl
