#include "world/radio_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"
#include "core/rng.h"

namespace rescuesim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The setter of one parameter: the field it writes, or the integer field.
struct Param {
  std::string_view key;
  double* value = nullptr;
  int* count = nullptr;
};

std::vector<Param> params_of(RadioModel& m) {
  switch (m.kind) {
    case RadioModelKind::wss:
      return {{"p0_dbm", &m.wss.p0_dbm},           {"d0_m", &m.wss.d0_m},
              {"n", &m.wss.n},                     {"wall_loss_db", &m.wss.wall_loss_db},
              {"max_walls", nullptr, &m.wss.max_walls}, {"cutoff_dbm", &m.wss.cutoff_dbm}};
    case RadioModelKind::subt:
      return {{"l0_db", &m.subt.l0_db},
              {"n", &m.subt.n},
              {"sigma_db", &m.subt.sigma_db},
              {"tx_power_dbm", &m.subt.tx_power_dbm},
              {"noise_floor_dbm", &m.subt.noise_floor_dbm},
              {"capacity_bps", &m.subt.capacity_bps},
              {"max_range_m", &m.subt.max_range_m}};
    case RadioModelKind::ideal:
      break;
  }
  return {};
}

}  // namespace

RadioModel radio_model(std::string_view name) {
  RadioModel m;
  if (name == "ideal") {
    m.kind = RadioModelKind::ideal;
  } else if (name == "wss") {
    m.kind = RadioModelKind::wss;
  } else if (name == "subt") {
    m.kind = RadioModelKind::subt;
  } else {
    throw Error(fmt::format("radio_model: unknown radio model '{}' (expected ideal, wss or subt)", name));
  }
  return m;
}

std::string_view radio_model_name(RadioModelKind kind) {
  switch (kind) {
    case RadioModelKind::wss: return "wss";
    case RadioModelKind::subt: return "subt";
    case RadioModelKind::ideal: break;
  }
  return "ideal";
}

std::optional<std::string> set_radio_parameter(RadioModel& model, std::string_view key, double value) {
  if (key == "max_datagram_bytes") {
    if (!(std::isfinite(value) && value == std::floor(value) && std::abs(value) < 9e15)) {
      return fmt::format("radio.{}.max_datagram_bytes: expected a whole number of bytes, got {}", radio_model_name(model.kind), value);
    }
    model.max_datagram_bytes = static_cast<std::int64_t>(value);
    return std::nullopt;
  }
  std::string known = "max_datagram_bytes";
  for (const Param& p : params_of(model)) {
    if (p.key != key) {
      known += fmt::format(", {}", p.key);
      continue;
    }
    if (p.count != nullptr) {
      if (!(std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e9)) {
        return fmt::format("radio.{}.{}: expected a whole number, got {}", radio_model_name(model.kind), key, value);
      }
      *p.count = static_cast<int>(value);
    } else {
      *p.value = value;
    }
    return std::nullopt;
  }
  return fmt::format("radio.{}: unknown parameter '{}' (known: {})", radio_model_name(model.kind), key, known);
}

std::vector<std::string> validate_radio_model(const RadioModel& model) {
  std::vector<std::string> errors;
  const std::string_view kind = radio_model_name(model.kind);
  // one message per rule broken: the parameter, the rule and the value given
  auto check = [&](bool ok, std::string_view key, std::string_view rule, double value) {
    if (!ok) errors.push_back(fmt::format("radio.{}.{}: must be {} (got {})", kind, key, rule, value));
  };
  auto finite = [](double v) { return std::isfinite(v); };
  switch (model.kind) {
    case RadioModelKind::wss: {
      const WssParams& p = model.wss;
      check(finite(p.p0_dbm), "p0_dbm", "finite", p.p0_dbm);
      check(finite(p.d0_m) && p.d0_m > 0, "d0_m", "finite and > 0", p.d0_m);
      check(finite(p.n) && p.n >= 0, "n", "finite and >= 0", p.n);
      check(finite(p.wall_loss_db) && p.wall_loss_db >= 0, "wall_loss_db", "finite and >= 0", p.wall_loss_db);
      check(p.max_walls >= 0, "max_walls", ">= 0", p.max_walls);
      check(finite(p.cutoff_dbm), "cutoff_dbm", "finite", p.cutoff_dbm);
      break;
    }
    case RadioModelKind::subt: {
      const SubtParams& p = model.subt;
      check(finite(p.l0_db), "l0_db", "finite", p.l0_db);
      check(finite(p.n) && p.n >= 0, "n", "finite and >= 0", p.n);
      check(finite(p.sigma_db) && p.sigma_db >= 0, "sigma_db", "finite and >= 0", p.sigma_db);
      check(finite(p.tx_power_dbm), "tx_power_dbm", "finite", p.tx_power_dbm);
      check(finite(p.noise_floor_dbm), "noise_floor_dbm", "finite", p.noise_floor_dbm);
      check(finite(p.capacity_bps) && p.capacity_bps > 0, "capacity_bps", "finite and > 0", p.capacity_bps);
      check(!std::isnan(p.max_range_m) && p.max_range_m > 0, "max_range_m", "> 0 (+inf for no limit)", p.max_range_m);
      break;
    }
    case RadioModelKind::ideal:
      break;
  }
  check(model.max_datagram_bytes > 0, "max_datagram_bytes", "> 0", static_cast<double>(model.max_datagram_bytes));
  return errors;
}

double received_power_dbm(const RadioModel& model, double distance_m, int walls, double shadowing_db) {
  if (std::isnan(distance_m)) return std::numeric_limits<double>::quiet_NaN();
  switch (model.kind) {
    case RadioModelKind::wss: {
      // closer than d0 receives the reference power: the model has nothing stronger
      const WssParams& p = model.wss;
      const double d = std::max(distance_m, p.d0_m);
      const int counted = std::clamp(walls, 0, p.max_walls);
      return p.p0_dbm - 10.0 * p.n * std::log10(d / p.d0_m) - counted * p.wall_loss_db + shadowing_db;
    }
    case RadioModelKind::subt: {
      // SubT's range model: nothing beyond max range, log-distance loss from 1 m
      const SubtParams& p = model.subt;
      if (distance_m > p.max_range_m) return -kInf;
      const double d = std::max(distance_m, 1.0);
      return p.tx_power_dbm - (p.l0_db + 10.0 * p.n * std::log10(d)) + shadowing_db;
    }
    case RadioModelKind::ideal:
      break;
  }
  return kInf;
}

double link_threshold_dbm(const RadioModel& model) {
  switch (model.kind) {
    case RadioModelKind::wss: return model.wss.cutoff_dbm;
    case RadioModelKind::subt: return model.subt.noise_floor_dbm;
    case RadioModelKind::ideal: break;
  }
  return -kInf;
}

bool has_shadowing(const RadioModel& model) { return model.kind == RadioModelKind::subt && model.subt.sigma_db > 0; }

double link_shadowing_db(const RadioModel& model, std::uint64_t seed, std::string_view id_a, std::string_view id_b,
                         std::uint64_t update_index) {
  if (!has_shadowing(model)) return 0.0;
  // the unordered pair names the stream; the update index moves its seed, so a draw depends
  // only on (seed, pair, update) and not on how many links were drawn before
  const std::string_view lo = std::min(id_a, id_b);
  const std::string_view hi = std::max(id_a, id_b);
  const std::string name = fmt::format("comms/shadowing/{}\x1f{}", lo, hi);
  Rng rng(splitmix64(seed ^ splitmix64(update_index + 0x5bd1e995ull)), name);
  return rng.normal(0.0, model.subt.sigma_db);
}

}  // namespace rescuesim
