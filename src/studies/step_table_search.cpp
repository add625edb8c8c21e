#include "studies/step_table_search.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <ostream>
#include <string>

#include "model/multibody_zmp.hpp"
#include "sim/closed_loop.hpp"
#include "studies/campaign_engine.hpp"

namespace biped {
namespace {

// Signed distance of a point to the edge of a foot's sole rectangle (positive inside).
double sole_margin(const RobotModel& model, Side side, const Eigen::Vector2d& point, const Eigen::Vector2d& ankle,
                   double yaw) {
  const FootInfo& foot = model.foot(side);
  const double sensor_x = model.mj()->site_pos[3 * foot.sensor_site];
  const double sensor_y = model.mj()->site_pos[3 * foot.sensor_site + 1];
  const Eigen::Vector2d d = point - ankle;
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double x = c * d.x() + s * d.y() - sensor_x, y = -s * d.x() + c * d.y() - sensor_y;
  return std::min({x - foot.sole_x_min, foot.sole_x_max - x, y - foot.sole_y_min, foot.sole_y_max - y});
}

// Margin inside the support polygon: the stance sole in single support; in double support the
// best of the soles swept from one foot to the other (the convex hull of the two rectangles).
double support_margin(const RobotModel& model, const PatternSample& s, const Eigen::Vector2d& zmp) {
  if (!s.feet[0].in_contact) return sole_margin(model, Side::Right, zmp, s.feet[1].position.head<2>(), s.feet[1].yaw);
  if (!s.feet[1].in_contact) return sole_margin(model, Side::Left, zmp, s.feet[0].position.head<2>(), s.feet[0].yaw);
  double best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 20; ++i) {
    const double a = i / 20.0;
    const Eigen::Vector2d ankle = (1 - a) * s.feet[0].position.head<2>() + a * s.feet[1].position.head<2>();
    const double yaw = s.feet[0].yaw + a * std::remainder(s.feet[1].yaw - s.feet[0].yaw, 2 * M_PI);
    best = std::max(best, sole_margin(model, a < 0.5 ? Side::Left : Side::Right, zmp, ankle, yaw));
  }
  return best;
}

// The first item (in order) for which `pred` holds, or null; evaluated `jobs` at a time in parallel,
// so the answer is the one a serial search gives.
template <class T, class Pred>
const T* first_where(const std::vector<const T*>& items, int jobs, const Pred& pred) {
  const std::size_t batch = static_cast<std::size_t>(jobs > 0 ? jobs : available_cores());
  for (std::size_t start = 0; start < items.size(); start += batch) {
    const long n = static_cast<long>(std::min(batch, items.size() - start));
    const std::vector<char> ok =
        parallel_map<char>(n, jobs, [&](long i) -> char { return pred(*items[start + static_cast<std::size_t>(i)]); });
    for (long i = 0; i < n; ++i) {
      if (ok[static_cast<std::size_t>(i)]) return items[start + static_cast<std::size_t>(i)];
    }
  }
  return nullptr;
}

}  // namespace

CandidateResult evaluate_step_candidate(const RobotModel& model, const WalkingControllerParams& base, double speed,
                                        double step_time, double double_support_ratio, int steps, int settle_steps,
                                        double zmp_window) {
  WalkingControllerParams params = base;
  params.stabilizer = false;
  params.sensor_limits.frozen_cycles = 0;  // the kinematic replay below feeds constant F/T and IMU readings
  params.plan.table = StepTable{};
  params.plan.limits.vx_max = std::max(params.plan.limits.vx_max, speed);  // judge the speed itself, unsaturated
  params.plan.step.step_time = step_time;
  params.plan.step.double_support_ratio = double_support_ratio;
  WalkingController controller(model, params);
  SensorData sensors(model.num_joints());
  sensors.joint_position = model.stand_pose();
  sensors.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
  for (Wrench& w : sensors.foot_wrench) w.force.z() = 0.5 * model.weight_above_sensors();
  controller.reset(sensors);
  JointCommand out(model.num_joints());
  RobotData data(model);
  const double dt = params.rmrc.dt;
  const double start = 0.5;
  const double duration = start + params.plan.start_shift + (steps + 1) * step_time;
  const double gait_start = start + params.plan.start_shift + settle_steps * step_time;
  const int com_row = TaskSpace(model).layout().com;
  std::deque<Eigen::VectorXd> history;
  // Criterion 2's ZMP is the mean over the last `window` cycles, weighted by the normal force (the
  // mean moment over the mean force). Each instant's ZMP lies in that instant's support, so the mean
  // lies in the hull of the window's supports: it is judged against the best of them (a lower bound).
  struct ZmpSample {
    Eigen::Vector2d weighted_zmp;
    double normal_force;
    PatternSample pattern;
  };
  const std::size_t window = static_cast<std::size_t>(std::max(1L, std::lround(zmp_window / dt)));
  std::deque<ZmpSample> recent;
  Eigen::Vector2d weighted_zmp_sum = Eigen::Vector2d::Zero();
  double normal_force_sum = 0.0;
  CandidateResult result;
  result.feasible = true;
  result.zmp_margin = std::numeric_limits<double>::infinity();
  for (int i = 0; i * dt < duration; ++i) {
    sensors.time = i * dt;
    WalkCommand command;
    command.vx = sensors.time >= start ? speed : 0.0;
    controller.step(sensors, command, out);
    sensors.joint_position = out.position;
    const ResolvedMotionRateControl& rmrc = controller.rmrc();
    if (rmrc.locked_joints() > 0 || rmrc.velocity_scale() < 1.0 ||
        (rmrc.x().segment<3>(com_row) - controller.pattern().com).norm() > 0.01) {
      result.feasible = false;
    }
    history.push_back(rmrc.qpos_d());
    if (history.size() > 3) history.pop_front();
    if (history.size() < 3 || (window == 1 && i % 10 != 0)) continue;  // each instant: every 10th is judged
    double normal_force = 0.0;
    const Eigen::Vector2d zmp = multibody_zmp(model, data, history[0], history[1], history[2], dt, &normal_force);
    recent.push_back({normal_force * zmp, normal_force, controller.pattern()});
    weighted_zmp_sum += recent.back().weighted_zmp;
    normal_force_sum += normal_force;
    if (recent.size() > window) {
      weighted_zmp_sum -= recent.front().weighted_zmp;
      normal_force_sum -= recent.front().normal_force;
      recent.pop_front();
    }
    const double centre_time = sensors.time - 0.5 * static_cast<double>(recent.size() - 1) * dt;
    if (recent.size() == window && i % 10 == 0 && centre_time >= gait_start) {
      const Eigen::Vector2d mean_zmp = weighted_zmp_sum / normal_force_sum;
      double margin = -std::numeric_limits<double>::infinity();
      for (const ZmpSample& r : recent) margin = std::max(margin, support_margin(model, r.pattern, mean_zmp));
      result.zmp_margin = std::min(result.zmp_margin, margin);
    }
  }
  return result;
}

bool survives_in_simulation(const RobotModel& model, const WalkingControllerParams& base,
                            const SimulationParams& sim_params, double speed, double turn_rate, double step_time,
                            double double_support_ratio, int steps) {
  WalkingControllerParams params = base;
  params.stabilizer = true;
  params.plan.table = StepTable{};
  params.plan.step.step_time = step_time;
  params.plan.step.double_support_ratio = double_support_ratio;
  params.plan.limits.vx_max = std::max(params.plan.limits.vx_max, speed);
  WalkingController controller(model, params);
  Simulation sim(sim_params, model);
  TimedCommand start;
  start.t = 0.5;
  start.command.vx = speed;
  start.command.omega = turn_rate;
  RunOptions options;
  options.duration = start.t + params.plan.start_shift + (steps + 1) * step_time;
  options.run_on_after_fall = 0.0;
  return !run_closed_loop(sim, controller, {TimedCommand{}, start}, options, nullptr).fell;
}

namespace {

// Chooses the gait of one speed by criteria 1–3, judging the ZMP averaged over `zmp_window`, among
// the step times within `max_step_time_change` of `neighbour_step_time` (all of them if none there
// is feasible, or if it is NaN). Fills `row`; false if no candidate passed (the row then holds the
// best candidate with a margin ≤ 0).
bool choose_row(const RobotModel& model, const WalkingControllerParams& base, const StepTableSearch& search,
                const SimulationParams* sim, double neighbour_step_time, double zmp_window, StepTableRow& row) {
  struct Candidate {
    double step_time, ds;
    CandidateResult result;
  };
  const double speed = row.speed;
  const bool windowed = !std::isnan(neighbour_step_time);
  auto evaluate = [&](bool in_window) {
    std::vector<Candidate> list;
    for (double step_time : search.step_times) {
      if (in_window && std::abs(step_time - neighbour_step_time) > search.max_step_time_change + 1e-9) continue;
      for (double ds : search.double_support_ratios) list.push_back({step_time, ds, {}});
    }
    const std::vector<CandidateResult> results =
        parallel_map<CandidateResult>(static_cast<long>(list.size()), search.jobs, [&](long i) {
          const Candidate& c = list[static_cast<std::size_t>(i)];
          return evaluate_step_candidate(model, base, speed, c.step_time, c.ds, search.steps, search.settle_steps,
                                         zmp_window);
        });
    for (std::size_t i = 0; i < list.size(); ++i) list[i].result = results[i];
    return list;
  };
  std::vector<Candidate> candidates = evaluate(windowed);
  if (windowed && std::none_of(candidates.begin(), candidates.end(), [](const Candidate& c) { return c.result.feasible; })) {
    candidates = evaluate(false);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.result.feasible != b.result.feasible) return a.result.feasible;
    return a.result.zmp_margin > b.result.zmp_margin;
  });
  auto survives = [&](const Candidate& c) {
    return !sim || survives_in_simulation(model, base, *sim, speed, search.turn_rate, c.step_time, c.ds, search.steps);
  };
  auto take = [&](const Candidate& c) {
    row.step_time = c.step_time;
    row.double_support_ratio = c.ds;
    row.zmp_margin = c.result.zmp_margin;
  };
  std::vector<const Candidate*> admissible;
  for (const Candidate& c : candidates) {
    if (!c.result.feasible || c.result.zmp_margin <= 0.0) break;
    admissible.push_back(&c);
  }
  const Candidate* best = first_where(admissible, search.jobs, survives);
  if (!best) {
    take(candidates.front());
    row.zmp_margin = std::min(0.0, row.zmp_margin);
    return false;
  }
  take(*best);
  // Longer (or shorter) steps where the margin is (nearly) as large, the longest (shortest) first.
  const double sign = search.prefer_short_steps ? -1.0 : 1.0;
  std::vector<const Candidate*> preferred;
  for (const Candidate& c : candidates) {
    if (c.result.feasible && sign * (c.step_time - row.step_time) > 1e-9 &&
        c.result.zmp_margin >= row.zmp_margin - search.margin_tolerance) {
      preferred.push_back(&c);
    }
  }
  std::stable_sort(preferred.begin(), preferred.end(),
                   [sign](const Candidate* a, const Candidate* b) { return sign * a->step_time > sign * b->step_time; });
  if (const Candidate* c = first_where(preferred, search.jobs, survives)) take(*c);
  return true;
}

// choose_row() with the robot file's swing travel share and, where that is below 1, again with the
// foot travelling the whole swing: the set-down share stays unless the whole-swing travel keeps more
// than `margin_tolerance` more ZMP margin or is the only one that passes. (Travelling in less time
// swings the leg harder: LOLA's 1.0 m/s row has no gait with 0.8, its 0.8 m/s row 24 mm against 45.)
bool choose_row_and_swing_travel(const RobotModel& model, const WalkingControllerParams& base,
                                 const StepTableSearch& search, const SimulationParams* sim,
                                 double neighbour_step_time, double zmp_window, StepTableRow& row) {
  row.swing_travel_share = base.plan.step.swing_travel_share;
  const bool feasible = choose_row(model, base, search, sim, neighbour_step_time, zmp_window, row);
  if (base.plan.step.swing_travel_share >= 1.0) return feasible;
  WalkingControllerParams whole_swing = base;
  whole_swing.plan.step.swing_travel_share = 1.0;
  StepTableRow alternative = row;
  alternative.swing_travel_share = 1.0;
  if (!choose_row(model, whole_swing, search, sim, neighbour_step_time, zmp_window, alternative)) return feasible;
  if (!feasible || alternative.zmp_margin > row.zmp_margin + search.margin_tolerance) row = alternative;
  return true;
}

void report_row(std::ostream* progress, const StepTableRow& row, bool feasible, double averaged_over) {
  if (!progress) return;
  *progress << "speed " << row.speed << " m/s: step time " << row.step_time << " s, double support "
            << row.double_support_ratio << ", swing travel share " << row.swing_travel_share << ", ZMP margin " << 1000.0 * row.zmp_margin << " mm"
            << (averaged_over > 0.0 ? " (ZMP averaged over " + std::to_string(averaged_over) + " s)" : "")
            << (feasible ? "" : " (no feasible candidate)") << '\n';
}

}  // namespace

StepTable generate_step_table(const RobotModel& model, const WalkingControllerParams& base,
                              const StepTableSearch& search, const SimulationParams* sim, std::ostream* progress) {
  std::vector<double> speeds = search.speeds;
  std::sort(speeds.begin(), speeds.end());
  const std::size_t n = speeds.size();
  std::vector<StepTableRow> rows(n);
  std::vector<char> feasible(n, 0);
  // From the fastest speed down, so each row's step time stays near the faster row's choice.
  double faster_step_time = std::numeric_limits<double>::quiet_NaN();  // NaN: no feasible faster row
  for (std::size_t k = n; k-- > 0;) {
    StepTableRow& row = rows[k];
    row.speed = speeds[k];
    row.clearance = base.plan.step.clearance;
    if (row.speed == 0.0) {
      // A zero command means standing (the FSM stops): no gait to choose. The row gives the stop
      // steps and, interpolated, the slowest walking: the nominal parameters, or with short steps
      // preferred the slowest walking row's (long stop steps left the robot on one foot 0.64 s
      // after a push and fell in place: docs/walking.md "Short steps"). It records that margin.
      const bool follow_slowest = search.prefer_short_steps && k + 1 < n && feasible[k + 1];
      row.step_time = follow_slowest ? rows[k + 1].step_time : base.plan.step.step_time;
      row.double_support_ratio =
          follow_slowest ? rows[k + 1].double_support_ratio : base.plan.step.double_support_ratio;
      row.swing_travel_share = follow_slowest ? rows[k + 1].swing_travel_share : base.plan.step.swing_travel_share;
      WalkingControllerParams stop = base;
      stop.plan.step.swing_travel_share = row.swing_travel_share;
      row.zmp_margin = evaluate_step_candidate(model, stop, 0.0, row.step_time, row.double_support_ratio, 1, 0,
                                               search.zmp_window).zmp_margin;
      feasible[k] = 1;
      continue;
    }
    feasible[k] = choose_row_and_swing_travel(model, base, search, sim, faster_step_time, search.zmp_window, row);
    report_row(progress, row, feasible[k], 0.0);
    faster_step_time = feasible[k] ? row.step_time : std::numeric_limits<double>::quiet_NaN();
  }
  // The relaxed criterion only adds rows above the ones that passed: from the slowest failed speed
  // up to the first that fails again, each near the next slower row's step time, so every row that
  // passed stays as it was.
  if (search.relaxed_zmp_window > 0.0) {
    for (std::size_t k = 1; k < n; ++k) {
      if (feasible[k]) continue;
      const double slower_step_time = feasible[k - 1] && rows[k - 1].speed > 0.0
                                          ? rows[k - 1].step_time
                                          : std::numeric_limits<double>::quiet_NaN();
      StepTableRow relaxed = rows[k];
      if (!choose_row_and_swing_travel(model, base, search, sim, slower_step_time, search.relaxed_zmp_window, relaxed)) {
        break;
      }
      rows[k] = relaxed;
      feasible[k] = 1;
      report_row(progress, relaxed, true, search.relaxed_zmp_window);
    }
  }
  StepTable table;
  table.rows = rows;
  return table;
}

}  // namespace biped
