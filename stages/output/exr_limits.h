#pragma once
// OpenEXR's own guard against huge images, set to the bound of our header walk
// (exr_header_scan.h). Both exist because each covers what the other cannot: the walk runs
// before the library allocates anything and also bounds width x height, while OpenEXR's limit
// (one per side) holds for every file the library opens, also in code that skips the walk.
namespace sl {

// Sets Imf::Header's maximum image and tile size (process-wide, once; later calls do nothing).
void limit_openexr_sizes();

}  // namespace sl
