#pragma once
// A small bitmap font for the live window's message banner (host/banner_text.h): printable ASCII, each glyph
// 5 pixels wide and 9 high (capitals and digits in rows 0 to 6, descenders in rows 7 and 8). Drawn on the CPU,
// so it needs no font file, no shader and nothing a software Vulkan driver might lack.

namespace gb {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 9;

// Whether pixel (x, y) of character `c`'s glyph is ink ((0, 0) top left). Characters outside printable ASCII
// (control characters, bytes of UTF-8 sequences) draw as '?'; pixels outside the glyph are never ink.
bool glyphInk(char c, int x, int y);

}  // namespace gb
