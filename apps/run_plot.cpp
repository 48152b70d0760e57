#include "run_plot.hpp"

#include <locale>
#include <sstream>

#include "sil_runner.hpp"

namespace gyro::sil {

namespace {

constexpr const char* kPitch = "#1f77b4";
constexpr const char* kYaw = "#ff7f0e";
constexpr const char* kPitchDark = "#0b3c5d";
constexpr const char* kYawDark = "#8c4a00";
constexpr const char* kGuidance = "#555555";
constexpr const char* kStop = "#d62728";
constexpr const char* kCone = "#222222";
constexpr const char* kLimit = "#9467bd";
constexpr const char* kUncage = "#2ca02c";
constexpr const char* kLatched = "#d62728";
constexpr const char* kFlag = "#4c72b0";
constexpr const char* kFaultWindow = "#f4a582";
constexpr const char* kFaultName = "#b2182b";
constexpr int kRowPx = 22;
constexpr int kCurvePanelPx = 210;
constexpr int kConePanelPx = 170;

std::string rgb(const char* c) { return std::string("lc rgb '") + c + "'"; }

std::string number(double v) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(4);
  s << v;
  return s.str();
}

const char* mode_color(GyroMode m) {
  switch (m) {
    case GyroMode::kIdle: return "#7f7f7f";
    case GyroMode::kCaged: return "#5b7fb5";
    case GyroMode::kUncaging: return "#17becf";
    case GyroMode::kFree: return "#2ca02c";
    case GyroMode::kFault: return "#d62728";
  }
  return "#000000";
}

PlotSeries series(const std::string& column, const std::string& title, const std::string& style) {
  return {csv_column(column), title, false, style, false};
}

// The pitch and yaw series of one quantity ("gimbal_pitch", "gimbal_yaw"), titled "pitch" +
// `what`; the main ones in the axes' colours, the others (`second`) in darker ones.
std::vector<PlotSeries> axes(const std::string& pitch_column, const std::string& yaw_column, const std::string& what,
                             const std::string& style, bool second = false) {
  return {series(pitch_column, "pitch" + what, style + " " + rgb(second ? kPitchDark : kPitch)),
          series(yaw_column, "yaw" + what, style + " " + rgb(second ? kYawDark : kYaw))};
}

std::vector<PlotSeries> operator+(std::vector<PlotSeries> a, const std::vector<PlotSeries>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

PlotPanel curves(const std::string& ylabel, std::vector<PlotSeries> series, int height_px = kCurvePanelPx) {
  PlotPanel p;
  p.ylabel = ylabel;
  p.series = std::move(series);
  p.height_px = height_px;
  return p;
}

// A limit line titled with its name and value.
PlotLimit limit(double value, const std::string& name, const std::string& style, bool mirrored) {
  return {value, name + " " + number(value), style, mirrored};
}

PlotPanel gimbal_panel() {
  return curves("gimbal angle (rad)", axes("gimbal_pitch", "gimbal_yaw", "", "lw 1.6") +
                                          axes("gimbal_pitch_pred", "gimbal_yaw_pred", " estimated", "lw 1 dt 2", true));
}

PlotPanel cone_panel(const Scenario& s) {
  PlotPanel p = curves("cone (rad)", {series("cone_true", "cone", "lw 2 " + rgb(kCone))}, kConePanelPx);
  const double cone = s.component.gimbal_cone_limit_rad;
  const double protect = cone - s.component.gimbal_stop_margin_rad;
  if (s.gyro.gimbal_stop_rad > 0) {
    p.limits.push_back(limit(s.gyro.gimbal_stop_rad, "stop", "lw 2 " + rgb(kStop), false));
  }
  p.limits.push_back(limit(cone, "cone limit", "dt 2 lw 1.2 " + rgb(kLimit), false));
  if (protect > 0) p.limits.push_back(limit(protect, "protection", "dt 3 lw 1 " + rgb(kLimit), false));
  return p;
}

PlotPanel rate_panel(const Scenario& s) {
  PlotPanel p = curves("precession rate (rad/s)", axes("theta_rate_true", "psi_rate_true", " flown", "lw 1.2") +
                                                      axes("rate_cmd_pitch", "rate_cmd_yaw", " commanded", "lw 1.4 dt 2", true));
  p.series.push_back(series("slew_cmd_pitch", "guidance's slew", "lw 1 dt 3 " + rgb(kGuidance)));
  p.series.push_back(series("slew_cmd_yaw", "", "lw 1 dt 3 " + rgb(kGuidance)));
  const double pitch = s.component.max_pitch_rate_rad_s, yaw = s.component.max_yaw_rate_rad_s;
  if (pitch == yaw) {
    p.limits.push_back(limit(pitch, "rate limit", "dt 2 lw 1.2 " + rgb(kLimit), true));
  } else {
    p.limits.push_back(limit(pitch, "pitch limit", "dt 2 lw 1.2 " + rgb(kPitch), true));
    p.limits.push_back(limit(yaw, "yaw limit", "dt 2 lw 1.2 " + rgb(kYaw), true));
  }
  return p;
}

PlotPanel torque_panel(const Scenario& s) {
  PlotPanel p = curves("torque", axes("torque_pitch", "torque_yaw", " commanded", "lw 1.4") +
                                    axes("torque_applied_pitch", "torque_applied_yaw", " applied", "lw 1 dt 2", true));
  p.limits.push_back(limit(s.component.max_torque, "max_torque", "dt 2 lw 1.2 " + rgb(kLimit), true));
  if (s.gyro.torquer.max_torque > 0 && s.gyro.torquer.max_torque != s.component.max_torque) {
    p.limits.push_back(limit(s.gyro.torquer.max_torque, "torquer saturation", "lw 1.5 " + rgb(kStop), true));
  }
  return p;
}

PlotPanel residual_panel(const Scenario& s) {
  PlotPanel p = curves("|residual| (rad)", axes("residual_pitch", "residual_yaw", "", "lw 1"));
  p.log_y = true;
  for (PlotSeries& a : p.series) a.magnitude = true;
  p.limits.push_back(limit(s.component.residual_limit_rad, "limit", "lw 2 " + rgb(kStop), false));
  return p;
}

std::vector<PlotBar> bars(const std::vector<TimeSpan>& spans, const char* color) {
  std::vector<PlotBar> out;
  out.reserve(spans.size());
  for (const TimeSpan& sp : spans) out.push_back({sp.from_s, sp.to_s, color, ""});
  return out;
}

PlotPanel raster_panel(const RunTimeline& t) {
  PlotPanel p;
  p.ylabel = "";
  PlotRow mode{"mode", {}};
  for (const ModeSpan& m : t.modes) {
    mode.bars.push_back({m.span.from_s, m.span.to_s, mode_color(m.mode), enum_name_or(m.mode, "?")});
  }
  p.rows.push_back(std::move(mode));
  for (int k = 1; k < kFaultKindCount; ++k) {
    const std::vector<TimeSpan>& f = t.faults[static_cast<std::size_t>(k)];
    if (!f.empty()) p.rows.push_back({std::string("fault ") + fault_kind_name(static_cast<FaultKind>(k)), bars(f, kStop)});
  }
  if (!t.at_stop.empty()) p.rows.push_back({"at stop (true)", bars(t.at_stop, kCone)});
  for (int b = 0; b < kComponentFlagCount; ++b) {
    const std::vector<TimeSpan>& f = t.flags[static_cast<std::size_t>(b)];
    if (f.empty()) continue;
    const bool latched = (1u << static_cast<unsigned>(b)) == kFaultLatched;
    p.rows.push_back({flag_name(b), bars(f, latched ? kLatched : kFlag)});
  }
  p.height_px = 50 + kRowPx * static_cast<int>(p.rows.size());
  return p;
}

}  // namespace

std::string scenario_title(const Scenario& s) {
  std::string title = std::filesystem::path(s.file).filename().string() + " (" + to_string(s.run.precision) + ")";
  std::string line;
  std::istringstream words(s.description);
  for (std::string w; words >> w;) {
    if (!line.empty() && line.size() + 1 + w.size() > 110) {
      title += "\n" + line;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) title += "\n" + line;
  return title;
}

PlotRequest run_plot(const std::filesystem::path& csv, const std::filesystem::path& png, const std::string& title,
                     const Scenario& s, const RunTimeline& t) {
  PlotRequest r;
  r.csv = csv;
  r.png = png;
  r.title = title;
  r.time_column = csv_column("t");
  r.end_s = t.end_s;
  const std::uint64_t rows = s.run.ticks + 1;
  r.every = (rows + kMaxPlottedRows - 1) / kMaxPlottedRows;
  if (r.every > 1) r.title += "\n(curves: one tick in " + std::to_string(r.every) + "; the raster: every tick)";
  r.panels = {gimbal_panel(), cone_panel(s), rate_panel(s), torque_panel(s), residual_panel(s), raster_panel(t)};
  for (int k = 1; k < kFaultKindCount; ++k) {
    const std::vector<TimeSpan>& spans = t.faults[static_cast<std::size_t>(k)];
    for (std::size_t i = 0; i < spans.size(); ++i) {
      // Named once: a fault that comes and goes is one name and several windows.
      const std::string name = i == 0 ? std::string(fault_kind_name(static_cast<FaultKind>(k))) + " injected at " +
                                            number(spans[i].from_s) + " s"
                                      : std::string();
      r.windows.push_back({spans[i].from_s, spans[i].to_s, name, kFaultWindow, kFaultName});
    }
  }
  if (t.uncage_s) r.markers.push_back({*t.uncage_s, "uncage " + number(*t.uncage_s) + " s", kUncage});
  if (t.latched_s) r.markers.push_back({*t.latched_s, "fault latched " + number(*t.latched_s) + " s", kLatched});
  if (t.stop_contact_s) r.markers.push_back({*t.stop_contact_s, "stop contact " + number(*t.stop_contact_s) + " s", kCone});
  return r;
}

}  // namespace gyro::sil
