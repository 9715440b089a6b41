// The gtkwave save file (.gtkw) by its content: the header keys, the zoom that fits the whole
// dump, the trace flag lines gtkwave reads (hex words, binary flags, analog reals with their
// extra rows, states through a translate filter), and the signal names gtkwave gives VCD vectors.
#include "ibs/vcd/gtkw_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace ibs::vcd {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

TEST(GtkwZoom, FitsTheDurationIntoTheWavePane) {
  // gtkwave: zoombase^-zoom ns per 200 pixels, zoombase 2.
  const double z = gtkw_zoom(8s, 800);
  EXPECT_NEAR(std::pow(2.0, -z) / 200.0 * 800.0, 8e9 + 1, 1.0);
  EXPECT_LT(gtkw_zoom(80s, 800), z);  // a longer run: zoomed further out
  EXPECT_EQ(gtkw_wave_pixels(GtkwLayout{}), 1400 - 220 - 300 - 120);
}

TEST(GtkwSave, ListsEverySignalInItsFormat) {
  std::ostringstream dump;
  VcdWriter vcd(dump);
  vcd.begin_scope("bus");
  const auto valid = vcd.add_wire("cycle_valid", 1, 1);
  vcd.end_scope();
  vcd.begin_scope("servo");
  const auto control = vcd.add_wire("control", 16);
  const auto status = vcd.add_wire("status", 16);
  const auto state = vcd.add_state("state", {"A", "B", "C"});
  const auto speed = vcd.add_real("speed_rpm");
  vcd.end_scope();

  GtkwSave g(vcd, "/runs/run.vcd", "/runs/run.vcd.gtkw", 8s);
  g.open_scope("bus");
  g.comment("bus");
  g.add(valid);
  g.comment("servo");
  g.add(state, "/runs/run.vcd.states.txt");
  g.add(speed, 3);
  g.add(control);
  g.add(status);
  const auto lines = lines_of(g.text());

  char zoom[64];
  std::snprintf(zoom, sizeof zoom, "*%.6f -1", gtkw_zoom(8s, gtkw_wave_pixels(GtkwLayout{})));
  const std::vector<std::string> head{
      "[*]",
      "[*] gtkwave save file written by ibs (docs/vcd.md): gtkwave /runs/run.vcd.gtkw",
      "[*]",
      "[dumpfile] \"/runs/run.vcd\"",
      "[savefile] \"/runs/run.vcd.gtkw\"",
      "[timestart] 0",
      "[size] 1400 900",
      "[pos] -1 -1",
      zoom,
      "[treeopen] bus.",
      "[sst_width] 220",
      "[signals_width] 300",
      "[sst_expanded] 1",
      "[sst_vpaned_height] 300",
  };
  ASSERT_GE(lines.size(), head.size());
  EXPECT_EQ(std::vector<std::string>(lines.begin(), lines.begin() + static_cast<long>(head.size())), head);
  const std::vector<std::string> traces{
      "@200",  // comment traces
      "-bus",
      "@28",  // binary, right-justified
      "bus.cycle_valid",
      "@200",
      "-servo",
      "@2022",  // translated through filter 1, hex
      "^1 /runs/run.vcd.states.txt",
      "servo.state[3:0]",
      "@88420",  // analog step over the whole dump's range, signed
      "servo.speed_rpm",
      "@20000",  // two more rows for the analog trace
      "-",
      "-",
      "@22",  // hex, right-justified; one flag line for both words
      "servo.control[15:0]",
      "servo.status[15:0]",
  };
  EXPECT_EQ(std::vector<std::string>(lines.begin() + static_cast<long>(head.size()), lines.end()), traces);
}

TEST(GtkwSave, FiltersAreNumberedInOrderOfFirstUse) {
  std::ostringstream dump;
  VcdWriter vcd(dump);
  vcd.begin_scope("a");
  const auto s1 = vcd.add_state("s1", {"X", "Y"});
  const auto s2 = vcd.add_state("s2", {"P", "Q"});
  const auto s3 = vcd.add_state("s3", {"X", "Y"});
  vcd.end_scope();
  GtkwSave g(vcd, "d.vcd", "d.gtkw", 1ms);
  g.add(s1, "xy.txt");
  g.add(s2, "pq.txt");
  g.add(s3, "xy.txt");
  const std::string t = g.text();
  EXPECT_NE(t.find("^1 xy.txt\na.s1[3:0]\n^2 pq.txt\na.s2[3:0]\n^1 xy.txt\na.s3[3:0]\n"), std::string::npos) << t;
}

}  // namespace
}  // namespace ibs::vcd
