#include "autonomy/scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace rescuesim::autonomy {

void LikelihoodField::build(const OccupancyMapper& grid, Cell lo, Cell hi, double sigma, double reach) {
  resolution_ = grid.resolution();
  origin_M_ = grid.origin();
  grid_w_ = grid.width();
  grid_h_ = grid.height();
  lo = {std::max(lo.x, 0), std::max(lo.y, 0)};
  hi = {std::min(hi.x, grid.width() - 1), std::min(hi.y, grid.height() - 1)};
  lo_ = lo;
  w_ = std::max(0, hi.x - lo.x + 1);
  h_ = std::max(0, hi.y - lo.y + 1);
  values_.assign(static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_), 0.0f);
  if (w_ == 0 || h_ == 0) return;

  // chamfer distance (cells) to the nearest occupied cell over the box widened by the reach,
  // so that walls just outside the box count: a forward and a backward pass with steps of 1
  // along rows and columns and sqrt(2) along diagonals
  const int m = static_cast<int>(std::ceil(reach / resolution_)) + 1;
  const Cell elo{std::max(lo.x - m, 0), std::max(lo.y - m, 0)};
  const Cell ehi{std::min(hi.x + m, grid.width() - 1), std::min(hi.y + m, grid.height() - 1)};
  const int ew = ehi.x - elo.x + 1, eh = ehi.y - elo.y + 1;
  constexpr float kFar = 1e9f;
  const float diag = static_cast<float>(std::sqrt(2.0));
  std::vector<float> d(static_cast<std::size_t>(ew) * static_cast<std::size_t>(eh), kFar);
  auto D = [&](int x, int y) -> float& { return d[static_cast<std::size_t>(y * ew + x)]; };
  for (int y = 0; y < eh; ++y) {
    for (int x = 0; x < ew; ++x) {
      if (grid.is_occupied({elo.x + x, elo.y + y})) D(x, y) = 0;
    }
  }
  for (int y = 0; y < eh; ++y) {
    for (int x = 0; x < ew; ++x) {
      float& v = D(x, y);
      if (x > 0) v = std::min(v, D(x - 1, y) + 1);
      if (y > 0) {
        v = std::min(v, D(x, y - 1) + 1);
        if (x > 0) v = std::min(v, D(x - 1, y - 1) + diag);
        if (x + 1 < ew) v = std::min(v, D(x + 1, y - 1) + diag);
      }
    }
  }
  for (int y = eh - 1; y >= 0; --y) {
    for (int x = ew - 1; x >= 0; --x) {
      float& v = D(x, y);
      if (x + 1 < ew) v = std::min(v, D(x + 1, y) + 1);
      if (y + 1 < eh) {
        v = std::min(v, D(x, y + 1) + 1);
        if (x + 1 < ew) v = std::min(v, D(x + 1, y + 1) + diag);
        if (x > 0) v = std::min(v, D(x - 1, y + 1) + diag);
      }
    }
  }

  // the Gaussian of the distance, inside the box
  const double k = -0.5 / (sigma * sigma);
  for (int y = 0; y < h_; ++y) {
    for (int x = 0; x < w_; ++x) {
      const double dist = D(lo.x + x - elo.x, lo.y + y - elo.y) * resolution_;
      values_[static_cast<std::size_t>(y * w_ + x)] = dist <= reach ? static_cast<float>(std::exp(k * dist * dist)) : 0.0f;
    }
  }
}

bool LikelihoodField::covers(const OccupancyMapper& grid, Cell lo, Cell hi) const {
  if (w_ == 0 || grid.resolution() != resolution_ || grid.origin() != origin_M_ || grid.width() != grid_w_ ||
      grid.height() != grid_h_) {
    return false;
  }
  // clipped to the grid as build clips it
  lo = {std::max(lo.x, 0), std::max(lo.y, 0)};
  hi = {std::min(hi.x, grid.width() - 1), std::min(hi.y, grid.height() - 1)};
  return lo.x >= lo_.x && lo.y >= lo_.y && hi.x < lo_.x + w_ && hi.y < lo_.y + h_;
}

double LikelihoodField::interpolate(const Vec2& p_M, Vec2* grad_M) const {
  // continuous cell coordinates with cell centres at integers
  const Vec2 u = (p_M - origin_M_) / resolution_ - Vec2(0.5, 0.5);
  const int x0 = static_cast<int>(std::floor(u.x())), y0 = static_cast<int>(std::floor(u.y()));
  const double fx = u.x() - x0, fy = u.y() - y0;
  const double v00 = at({x0, y0}), v10 = at({x0 + 1, y0}), v01 = at({x0, y0 + 1}), v11 = at({x0 + 1, y0 + 1});
  if (grad_M) {
    *grad_M = Vec2((1 - fy) * (v10 - v00) + fy * (v11 - v01), (1 - fx) * (v01 - v00) + fx * (v11 - v10)) / resolution_;
  }
  return (1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11);
}

ScanMatcher::ScanMatcher(ScanMatcherConfig config) : config_(config) {}

double ScanMatcher::mean_field(const std::vector<Vec2>& p_B, const Pose2& X_MB) const {
  double sum = 0;
  for (const Vec2& p : p_B) sum += field_.interpolate(X_MB.transform(p));
  return p_B.empty() ? 0.0 : sum / static_cast<double>(p_B.size());
}

ScanMatch ScanMatcher::match(const OccupancyMapper& grid, const std::vector<Vec2>& all_p_B, const Pose2& X_MB_predicted) {
  ScanMatch m;
  m.X_MB_predicted = m.X_MB_best = m.X_MB = X_MB_predicted;

  // the points in reach, thinned evenly
  std::vector<Vec2> near;
  for (const Vec2& p : all_p_B) {
    if (p.norm() <= config_.max_range) near.push_back(p);
  }
  std::vector<Vec2> p_B;
  const std::size_t cap = static_cast<std::size_t>(std::max(config_.max_points, 1));
  if (near.size() <= cap) {
    p_B = std::move(near);
  } else {
    for (std::size_t i = 0; i < cap; ++i) p_B.push_back(near[i * near.size() / cap]);
  }
  m.points = static_cast<int>(p_B.size());
  if (!grid.allocated() || m.points < std::max(config_.min_points, 1)) return m;

  // the field over every cell a point can reach within the window
  const double res = grid.resolution();
  double far = 0;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec2& p : p_B) {
    const Vec2 q = X_MB_predicted.transform(p);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
    far = std::max(far, p.norm());
  }
  const double pad = config_.search_xy + far * config_.search_yaw + 2 * res;
  const auto to_cell = [&](const Vec2& q) {
    const Vec2 u = (q - grid.origin()) / res;
    return Cell{static_cast<int>(std::floor(u.x())), static_cast<int>(std::floor(u.y()))};
  };
  // the field is rebuilt for every match, or (field_refresh > 1) over a wider box kept for
  // that many matches while the points stay inside it: the map changes little in a few scans
  const Cell need_lo = to_cell(lo - Vec2::Constant(pad)), need_hi = to_cell(hi + Vec2::Constant(pad));
  const bool inside = field_.covers(grid, need_lo, need_hi);
  if (config_.field_refresh <= 1 || !inside || field_uses_ >= config_.field_refresh) {
    const double margin = config_.field_refresh > 1 ? config_.field_margin : 0.0;
    field_.build(grid, to_cell(lo - Vec2::Constant(pad + margin)), to_cell(hi + Vec2::Constant(pad + margin)), config_.field_sigma,
                 config_.field_reach);
    field_uses_ = 0;
  }
  ++field_uses_;

  // correlative search: every heading of the window, and for each every shift by whole cells;
  // per shift the best heading is kept for the spread of near-best candidates
  const int n_xy = std::max(0, static_cast<int>(std::lround(config_.search_xy / res)));
  const int n_yaw = config_.yaw_step > 0 ? std::max(0, static_cast<int>(std::lround(config_.search_yaw / config_.yaw_step))) : 0;
  const int side = 2 * n_xy + 1;
  std::vector<double> shift_best(static_cast<std::size_t>(side * side), -1.0);
  std::vector<Cell> cells(p_B.size());
  double best = -1;
  int best_i = 0, best_j = 0, best_k = 0;
  double best_rank = std::numeric_limits<double>::infinity();
  const double inv_n = 1.0 / static_cast<double>(p_B.size());
  for (int k = -n_yaw; k <= n_yaw; ++k) {
    const Pose2 X{X_MB_predicted.x, X_MB_predicted.y, X_MB_predicted.yaw + k * config_.yaw_step};
    for (std::size_t p = 0; p < p_B.size(); ++p) cells[p] = to_cell(X.transform(p_B[p]));
    for (int j = -n_xy; j <= n_xy; ++j) {
      for (int i = -n_xy; i <= n_xy; ++i) {
        double sum = 0;
        for (const Cell& c : cells) sum += field_.at({c.x + i, c.y + j});
        const double s = sum * inv_n;
        double& sb = shift_best[static_cast<std::size_t>((j + n_xy) * side + (i + n_xy))];
        sb = std::max(sb, s);
        // ties go to the candidate nearest the prediction (in cells and yaw steps)
        const double rank = i * i + j * j + k * k;
        if (s > best + 1e-12 || (s > best - 1e-12 && rank < best_rank)) {
          best = s;
          best_i = i, best_j = j, best_k = k;
          best_rank = rank;
        }
      }
    }
  }

  // the spread of the near-best shifts: their positions' covariance and its axes
  double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int j = -n_xy; j <= n_xy; ++j) {
    for (int i = -n_xy; i <= n_xy; ++i) {
      if (shift_best[static_cast<std::size_t>((j + n_xy) * side + (i + n_xy))] < config_.near_best * best) continue;
      const double x = i * res, y = j * res;
      n += 1;
      sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
    }
  }
  const double cxx = sxx / n - (sx / n) * (sx / n), cyy = syy / n - (sy / n) * (sy / n), cxy = sxy / n - (sx / n) * (sy / n);
  const double mid = 0.5 * (cxx + cyy), rad = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
  m.spread_major = std::sqrt(std::max(0.0, mid + rad));
  m.spread_minor = std::sqrt(std::max(0.0, mid - rad));
  const double axis = 0.5 * std::atan2(2 * cxy, cxx - cyy);
  m.major_axis_M = Vec2(std::cos(axis), std::sin(axis));

  // refinement: Gauss-Newton on the interpolated field (Hector SLAM's step), each step kept
  // only when it raises the mean field, and never more than one search step from the best
  // candidate (the search already chose the basin; this only finds the bottom of it)
  const Pose2 coarse{X_MB_predicted.x + best_i * res, X_MB_predicted.y + best_j * res,
                     wrap_angle(X_MB_predicted.yaw + best_k * config_.yaw_step)};
  Pose2 X = coarse;
  double score = mean_field(p_B, X);
  for (int it = 0; it < config_.refine_iterations; ++it) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    const double c = std::cos(X.yaw), s = std::sin(X.yaw);
    for (const Vec2& p : p_B) {
      Vec2 grad;
      const double v = field_.interpolate(X.transform(p), &grad);
      // d(point)/d(yaw) for the rotation about the pose's origin
      const Vec2 dq(-s * p.x() - c * p.y(), c * p.x() - s * p.y());
      const Eigen::Vector3d J(grad.x(), grad.y(), grad.dot(dq));
      H += J * J.transpose();
      g += J * (1.0 - v);
    }
    // a little damping keeps the unconstrained direction of a corridor from running off
    H.diagonal() += Eigen::Vector3d::Constant(1e-3 * (H.trace() + 1e-9));
    const Eigen::Vector3d step = H.ldlt().solve(g);
    if (!step.allFinite()) break;
    Pose2 next{X.x + step.x(), X.y + step.y(), wrap_angle(X.yaw + step.z())};
    next.x = std::clamp(next.x, coarse.x - res, coarse.x + res);
    next.y = std::clamp(next.y, coarse.y - res, coarse.y + res);
    next.yaw = coarse.yaw + std::clamp(wrap_angle(next.yaw - coarse.yaw), -config_.yaw_step, config_.yaw_step);
    const double next_score = mean_field(p_B, next);
    if (!(next_score > score)) break;
    X = next;
    score = next_score;
  }
  m.X_MB_best = X;
  m.score = score;
  m.predicted_score = mean_field(p_B, X_MB_predicted);

  // the verdict: a poor fit, or nothing pinned down, keeps the prediction; one loose direction
  // (a corridor) corrects only the heading and the direction across it
  if (score < config_.min_score || m.spread_minor > config_.max_spread) return m;
  if (m.spread_major > config_.max_spread) {
    const Vec2 across(-m.major_axis_M.y(), m.major_axis_M.x());
    const Vec2 p = X_MB_predicted.position() + across.dot(X.position() - X_MB_predicted.position()) * across;
    m.X_MB = {p.x(), p.y(), X.yaw};
    m.verdict = MatchVerdict::ambiguous;
    return m;
  }
  m.X_MB = X;
  m.verdict = MatchVerdict::good;
  return m;
}

}  // namespace rescuesim::autonomy
