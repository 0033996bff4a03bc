#include "pictures.h"

#include <algorithm>
#include <cctype>

#include "stages/output/tone_map.h"

namespace report {
namespace {

// 5x7 glyphs, one string per glyph: 7 rows of 5 columns, '#' = ink. Lower case letters keep
// their body in the lower rows; letters with descenders sit one row higher.
struct Glyph {
    char c;
    const char* rows;  // 35 characters, row by row
};
constexpr Glyph kFont[] = {
    {' ', "..................................."},
    {'0', ".###.#...##..###.#.###..##...#.###."},
    {'1', "..#...##....#....#....#....#...###."},
    {'2', ".###.#...#....#...#...#...#...#####"},
    {'3', "#####...#...#.....#.....##...#.###."},
    {'4', "...#...##..#.#.#..#.#####...#....#."},
    {'5', "######....####.....#....##...#.###."},
    {'6', "..##..#...#....####.#...##...#.###."},
    {'7', "#####....#...#...#...#....#....#..."},
    {'8', ".###.#...##...#.###.#...##...#.###."},
    {'9', ".###.#...##...#.####....#...#..##.."},
    {'a', "...........###.....#.#####...#.####"},
    {'b', "#....#....#.##.##..##...##...#####."},
    {'c', "...........###.#....#....#...#.###."},
    {'d', "....#....#.##.##..###...##...#.####"},
    {'e', "...........###.#...#######.....###."},
    {'f', "..##..#..#.#...###...#....#....#..."},
    {'g', "......#####...##...#.####....#.###."},
    {'h', "#....#....#.##.##..##...##...##...#"},
    {'i', "..#........##....#....#....#...###."},
    {'j', "...#........##....#....#.#..#..##.."},
    {'k', "#....#....#..#.#.#..##...#.#..#..#."},
    {'l', ".##....#....#....#....#....#...###."},
    {'m', "..........##.#.#.#.##.#.##...##...#"},
    {'n', "..........#.##.##..##...##...##...#"},
    {'o', "...........###.#...##...##...#.###."},
    {'p', ".....####.#...##...#####.#....#...."},
    {'q', "......#####...##...#.####....#....#"},
    {'r', "..........#.##.##..##....#....#...."},
    {'s', "...........#####.....###.....#####."},
    {'t', ".#....#...###...#....#....#..#..##."},
    {'u', "..........#...##...##...##..##.##.#"},
    {'v', "..........#...##...##...#.#.#...#.."},
    {'w', "..........#...##...##.#.##.#.#.#.#."},
    {'x', "..........#...#.#.#...#...#.#.#...#"},
    {'y', ".....#...##...##...#.####....#.###."},
    {'z', "..........#####...#...#...#...#####"},
    {'.', "..........................##...##.."},
    {',', ".....................##....#...#..."},
    {'-', "...............#####..............."},
    {'+', ".......#....#..#####..#....#......."},
    {':', "......##...##........##...##......."},
    {'=', "..........#####.....#####.........."},
    {'<', "...#...#...#...#.....#.....#.....#."},
    {'>', ".#.....#.....#.....#...#...#...#..."},
    {'#', ".#.#..#.#.#####.#.#.#####.#.#..#.#."},
    {'(', "..#...#...#....#....#.....#.....#.."},
    {')', "..#.....#.....#....#....#...#...#.."},
    {'[', ".###..#....#....#....#....#....###."},
    {']', ".###....#....#....#....#....#..###."},
    {'/', ".........#...#...#...#...#........."},
    {'%', "##...##..#...#...#...#...#..##...##"},
    {'_', "..............................#####"},
    {'\'', "..#....#...#......................."},
};

constexpr bool glyphs_are_5x7() {
    for (const Glyph& g : kFont) {
        int n = 0;
        while (g.rows[n]) ++n;
        if (n != 35) return false;
    }
    return true;
}
static_assert(glyphs_are_5x7(), "every glyph is 7 rows of 5 cells");

const char* glyph(char c) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const Glyph& g : kFont)
        if (g.c == c) return g.rows;
    return nullptr;
}

}  // namespace

bool font_has(char c) { return glyph(c) != nullptr; }

int text_width(const std::string& s, int scale) { return static_cast<int>(s.size()) * 6 * scale; }

void Canvas::put(int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    p[0] = r; p[1] = g; p[2] = b;
}

void Canvas::blit(const uint8_t* src, int w, int h, int x0, int y0, int scale) {
    for (int y = 0; y < h * scale; ++y)
        for (int x = 0; x < w * scale; ++x) {
            const uint8_t* s = &src[(static_cast<size_t>(y / scale) * w + x / scale) * 3];
            put(x0 + x, y0 + y, s[0], s[1], s[2]);
        }
}

int Canvas::text(const std::string& s, int x0, int y0, int scale, uint8_t r, uint8_t g, uint8_t b) {
    int x = x0;
    for (char c : s) {
        const char* rows = glyph(c);
        if (!rows) rows = glyph('#');  // a visible placeholder for a missing glyph
        for (int gy = 0; gy < kGlyphH; ++gy)
            for (int gx = 0; gx < 5; ++gx) {
                size_t i = static_cast<size_t>(gy * 5 + gx);
                if (rows[i] == '#')
                    for (int dy = 0; dy < scale; ++dy)
                        for (int dx = 0; dx < scale; ++dx) put(x + gx * scale + dx, y0 + gy * scale + dy, r, g, b);
            }
        x += 6 * scale;
    }
    return x - x0;
}

Canvas contact_sheet(const std::vector<Tile>& tiles, int w, int h, double exposure, int columns,
                     const std::string& title, int min_tile_px) {
    const int up = std::max(1, (min_tile_px + w - 1) / w);
    const int tw = w * up, th = h * up;
    const int pad = 4, caption_h = kGlyphH + 6;
    const int title_h = title.empty() ? 0 : 2 * kGlyphH + 8;
    columns = std::max(1, std::min<int>(columns, static_cast<int>(tiles.size())));
    const int rows = static_cast<int>((tiles.size() + columns - 1) / columns);
    Canvas c(pad + columns * (tw + pad), title_h + pad + rows * (th + caption_h + pad), 24);
    if (!title.empty()) c.text(title, pad, pad, 2, 230, 230, 230);
    std::vector<uint8_t> rgb8(static_cast<size_t>(w) * h * 3);
    for (size_t i = 0; i < tiles.size(); ++i) {
        int col = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
        int x0 = pad + col * (tw + pad), y0 = title_h + pad + row * (th + caption_h + pad);
        sl::tone_map_srgb8(tiles[i].linear->data(), w, h, exposure, rgb8.data());
        c.blit(rgb8.data(), w, h, x0, y0, up);
        // Captions are cut to the tile's width rather than spilling into the next tile.
        std::string cap = tiles[i].caption;
        while (!cap.empty() && text_width(cap) > tw) cap.pop_back();
        c.text(cap, x0 + (tw - text_width(cap)) / 2, y0 + th + 3, 1, 235, 235, 200);
    }
    return c;
}

}  // namespace report
