// Runs gnuplot (Debian `gnuplot-nox`) as a process on a script written to a temporary file and
// collects the image it writes to its standard output (docs/simulator.md, "Plots").
#pragma once

#include <ostream>
#include <string>

namespace ibs::cli {

// Whether an executable `gnuplot` is on the PATH.
bool gnuplot_available();

// Runs `gnuplot SCRIPT`; its standard output goes to `image`. False with `error` set (gnuplot
// missing, failing, or writing nothing; its first error lines quoted).
bool run_gnuplot(const std::string& script, std::ostream& image, std::string& error);

}  // namespace ibs::cli
