#pragma once
// Pictures for the report: 8-bit RGB canvases, a tiny built-in 5x7 bitmap font (so that no
// font file or text-rendering library is needed), and contact sheets of tone-mapped frames
// with a caption under each tile.
#include <cstdint>
#include <string>
#include <vector>

namespace report {

struct Canvas {
    Canvas(int w, int h, uint8_t grey = 0) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, grey) {}
    int width, height;
    std::vector<uint8_t> rgb;  // row 0 at the top

    void put(int x, int y, uint8_t r, uint8_t g, uint8_t b);
    // Copies a w x h sRGB image at (x0, y0), each source pixel as a scale x scale block.
    void blit(const uint8_t* src, int w, int h, int x0, int y0, int scale = 1);
    // Draws text with the 5x7 font, each font pixel a scale x scale block; returns the width.
    int text(const std::string& s, int x0, int y0, int scale = 1, uint8_t r = 255, uint8_t g = 255, uint8_t b = 255);
};

// Width in pixels of a string drawn at `scale` (6 pixels per character, 1 of them spacing).
int text_width(const std::string& s, int scale = 1);
constexpr int kGlyphH = 7;
// True when the font has a glyph for c (lower case, digits and a few symbols; upper case is
// drawn as lower case).
bool font_has(char c);

struct Tile {
    const std::vector<float>* linear = nullptr;  // w*h*3 linear radiance
    std::string caption;
};

// Tone-maps every tile with one exposure, upscales images narrower than min_tile_px by an
// integer factor, and tiles them `columns` across with the caption under each. `title` (may
// be empty) goes across the top.
Canvas contact_sheet(const std::vector<Tile>& tiles, int w, int h, double exposure, int columns,
                     const std::string& title, int min_tile_px = 128);

}  // namespace report
