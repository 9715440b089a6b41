// A gtkwave save file (.gtkw) for a dump written by VcdWriter: which signals gtkwave shows, in
// which format, with which translate filter, at which zoom. `gtkwave FILE.gtkw` (or
// `gtkwave DUMP FILE.gtkw`) then opens the dump ready to read instead of an empty window
// (docs/vcd.md, "The save file"). The syntax is gtkwave's own: `[key] value` lines, a `*zoom
// marker` line, `@flags` lines (gtkwave's TR_* trace flag bits, in hex) that apply to the signal
// lines after them, `^N FILE` translate filter lines, `-text` comment lines.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/time.hpp"
#include "ibs/vcd/vcd_writer.hpp"

namespace ibs::vcd {

// gtkwave's trace flags (its analyzer.h, TR_*), the ones a save file of ours uses.
namespace gtkw_flags {
inline constexpr std::uint32_t kHex = 0x2;
inline constexpr std::uint32_t kBinary = 0x8;
inline constexpr std::uint32_t kRightJustify = 0x20;
inline constexpr std::uint32_t kBlank = 0x200;  // a comment (or blank) trace
inline constexpr std::uint32_t kSigned = 0x400;
inline constexpr std::uint32_t kTranslated = 0x2000;  // through a translate filter file
inline constexpr std::uint32_t kAnalogStep = 0x8000;
inline constexpr std::uint32_t kAnalogBlankStretch = 0x20000;  // the rows that make an analog trace taller
// Resizing > All Data: an analog trace scaled to its values over the whole dump, not the window's.
inline constexpr std::uint32_t kAnalogFullscale = 0x80000;
}  // namespace gtkw_flags

struct GtkwLayout {
  int width = 1400;          // the window, pixels
  int height = 900;
  int sst_width = 220;       // the signal search tree on the left
  int signals_width = 300;   // the signal names
};

// The zoom gtkwave shows `duration` with in `wave_pixels` of wave pane: gtkwave draws
// zoombase^-zoom nanoseconds (the dump's time unit) per 200 pixels, zoombase 2 by default, so
// zoom = -log2(duration * 200 / wave_pixels) (its "zoom best fit" does the same).
double gtkw_zoom(Duration duration, int wave_pixels);
// The wave pane a layout leaves, less a margin for gtkwave's frames and scrollbar.
int gtkw_wave_pixels(const GtkwLayout& layout);

class GtkwSave {
 public:
  // `vcd` names the signals (its paths and widths); `dumpfile` and `savefile` are written into
  // the file as given (absolute paths let gtkwave find the dump from anywhere); `end` is the
  // dump's last time: the zoom shows 0..end.
  GtkwSave(const VcdWriter& vcd, std::string dumpfile, std::string savefile, Time end, GtkwLayout layout = {});

  // The scope is shown expanded in the signal search tree.
  void open_scope(std::string_view scope);
  // A heading line among the traces.
  void comment(std::string_view text);
  // A wire in hex (binary for one bit).
  void add(WireSignal s);
  // A real as an analog step trace, `rows` trace rows tall.
  void add(RealSignal s, int rows = 3);
  // A state through the translate filter file `filter` (its values shown by name).
  void add(StateSignal s, const std::string& filter);

  // The whole file.
  [[nodiscard]] std::string text() const;

 private:
  void flags(std::uint32_t f);

  const VcdWriter& vcd_;
  std::string dumpfile_;
  std::string savefile_;
  Time end_;
  GtkwLayout layout_;
  std::vector<std::string> scopes_;
  std::vector<std::string> filters_;  // ^1, ^2, ... in order of first use
  std::string traces_;
  std::uint32_t flags_ = 0xFFFFFFFF;  // the flags the last @ line set
};

}  // namespace ibs::vcd
