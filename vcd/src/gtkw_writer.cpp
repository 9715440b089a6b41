#include "ibs/vcd/gtkw_writer.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace ibs::vcd {

double gtkw_zoom(Duration duration, int wave_pixels) {
  const double ns = std::max(1.0, static_cast<double>(duration.count()) + 1.0);
  const double pixels = std::max(1.0, static_cast<double>(wave_pixels));
  return -std::log2(ns * 200.0 / pixels);
}

int gtkw_wave_pixels(const GtkwLayout& l) { return std::max(100, l.width - l.sst_width - l.signals_width - 120); }

GtkwSave::GtkwSave(const VcdWriter& vcd, std::string dumpfile, std::string savefile, Time end, GtkwLayout layout)
    : vcd_(vcd), dumpfile_(std::move(dumpfile)), savefile_(std::move(savefile)), end_(end), layout_(layout) {}

void GtkwSave::open_scope(std::string_view scope) { scopes_.emplace_back(scope); }

void GtkwSave::flags(std::uint32_t f) {
  if (f == flags_) return;
  char buf[16];
  std::snprintf(buf, sizeof buf, "@%" PRIx32 "\n", f);
  traces_ += buf;
  flags_ = f;
}

void GtkwSave::comment(std::string_view text) {
  flags(gtkw_flags::kBlank);
  traces_ += '-';
  traces_ += text;
  traces_ += '\n';
}

void GtkwSave::add(WireSignal s) {
  const unsigned w = vcd_.width(s);
  flags((w == 1 ? gtkw_flags::kBinary : gtkw_flags::kHex) | gtkw_flags::kRightJustify);
  traces_ += vcd_.path(s);
  if (w > 1) traces_ += "[" + std::to_string(w - 1) + ":0]";
  traces_ += '\n';
}

void GtkwSave::add(RealSignal s, int rows) {
  flags(gtkw_flags::kAnalogStep | gtkw_flags::kAnalogFullscale | gtkw_flags::kSigned | gtkw_flags::kRightJustify);
  traces_ += vcd_.path(s);
  traces_ += '\n';
  if (rows > 1) {
    flags(gtkw_flags::kAnalogBlankStretch);
    for (int i = 1; i < rows; ++i) traces_ += "-\n";
  }
}

void GtkwSave::add(StateSignal s, const std::string& filter) {
  auto it = std::find(filters_.begin(), filters_.end(), filter);
  if (it == filters_.end()) it = filters_.insert(filters_.end(), filter);
  const auto n = static_cast<std::size_t>(it - filters_.begin()) + 1;
  flags(gtkw_flags::kTranslated | gtkw_flags::kHex | gtkw_flags::kRightJustify);
  traces_ += "^" + std::to_string(n) + " " + filter + "\n";
  traces_ += vcd_.path(s);
  traces_ += "[" + std::to_string(vcd_.width(s) - 1) + ":0]\n";
}

std::string GtkwSave::text() const {
  std::string t;
  t += "[*]\n[*] gtkwave save file written by ibs (docs/vcd.md): gtkwave " + savefile_ + "\n[*]\n";
  t += "[dumpfile] \"" + dumpfile_ + "\"\n";
  t += "[savefile] \"" + savefile_ + "\"\n";
  t += "[timestart] 0\n";
  t += "[size] " + std::to_string(layout_.width) + " " + std::to_string(layout_.height) + "\n";
  t += "[pos] -1 -1\n";
  char zoom[64];
  std::snprintf(zoom, sizeof zoom, "*%.6f -1\n", gtkw_zoom(end_, gtkw_wave_pixels(layout_)));
  t += zoom;
  for (const auto& s : scopes_) t += "[treeopen] " + s + ".\n";
  t += "[sst_width] " + std::to_string(layout_.sst_width) + "\n";
  t += "[signals_width] " + std::to_string(layout_.signals_width) + "\n";
  t += "[sst_expanded] 1\n";
  t += "[sst_vpaned_height] " + std::to_string(layout_.height / 3) + "\n";
  t += traces_;
  return t;
}

}  // namespace ibs::vcd
