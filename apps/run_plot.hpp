// The plot of one run, as gyro_sil --plot, gyro_campaign --run K and a processor-in-the-loop
// run draw it: panels on one time axis, each with the limit it is judged against.
//   gimbal    the true gimbal angles (lines) and the component's estimate (dashed)
//   cone      the true cone against the stop, the cone limit and the protection cone below it
//   rate      the spin axis's true precession rate (flown) against the rate the torque law
//             commanded (after its limits and the stop protection) and guidance's slew
//   torque    commanded and applied (after the torquer's electronics and faults) against
//             the component's max_torque and the torquer's saturation
//   residual  |measured - predicted| per axis, log scale, against residual_limit_rad
//   raster    the mode band, the faults injected, the gimbal on its stop, each flag raised
// Markers through every panel: the uncage request, the fault latched, the first stop
// contact; each injected fault's window is shaded.
#pragma once

#include <filesystem>
#include <string>

#include "plot.hpp"
#include "run_timeline.hpp"
#include "scenario.hpp"

namespace gyro::sil {

// A long run is plotted every Nth row: at most this many rows a series (the image is 1200
// pixels wide); the raster comes from every tick (run_timeline.hpp).
inline constexpr std::uint64_t kMaxPlottedRows = 20000;

// The plot of the run of `s` whose CSV is `csv` and timeline `t`, titled `title`.
[[nodiscard]] PlotRequest run_plot(const std::filesystem::path& csv, const std::filesystem::path& png,
                                   const std::string& title, const Scenario& s, const RunTimeline& t);

// A scenario's title: its file name and precision, then its description wrapped at words.
[[nodiscard]] std::string scenario_title(const Scenario& s);

}  // namespace gyro::sil
