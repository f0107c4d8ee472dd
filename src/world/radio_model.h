#pragma once
/// Radio link models of rescue competitions, chosen by name: `ideal` (always connected),
/// `wss` (RoboCup's USARSim-era Wireless Simulation Server) and `subt` (DARPA SubT's
/// log-normal range model). Plain data with defaults, a validation that names each bad
/// parameter, and the received power as a pure function. Powers in dBm, losses in dB,
/// distances in metres.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rescuesim {

/// Which link model a RadioModel uses.
enum class RadioModelKind { ideal, wss, subt };

/// The WSS model: P = p0 − 10·n·log10(d/d0) − min(walls, max_walls)·wall_loss, link if P ≥ cutoff.
struct WssParams {
  double p0_dbm = -49.67;       ///< received power at the reference distance (dBm)
  double d0_m = 2.0;            ///< reference distance (m); closer radios receive p0
  double n = 1.0;               ///< path-loss exponent
  double wall_loss_db = 6.325;  ///< loss per wall (dB)
  int max_walls = 5;            ///< walls counted at most
  double cutoff_dbm = -93.0;    ///< weakest received power that still links (dBm)
};

/// The SubT model: P = tx − (l0 + 10·n·log10(d)) + shadowing, link if P ≥ noise floor;
/// walls are not part of it. Each radio carries at most `capacity_bps` (sent and received
/// counted separately, over a sliding one-second window); datagrams beyond it are dropped.
struct SubtParams {
  double l0_db = 40.0;             ///< path loss at 1 m (dB)
  double n = 1.5;                  ///< path-loss exponent
  double sigma_db = 10.0;          ///< standard deviation of the Gaussian shadowing (dB)
  double tx_power_dbm = 20.0;      ///< transmit power (dBm)
  double noise_floor_dbm = -90.0;  ///< weakest received power that still links (dBm)
  double capacity_bps = 1e6;       ///< channel capacity of one radio (bit/s)
  double max_range_m = 500.0;      ///< no link beyond this distance (m); +inf = no limit
};

/// A radio link model and its parameters. Every field may be overridden after
/// radio_model(name) (directly or through set_radio_parameter); validate_radio_model says
/// which values are impossible.
struct RadioModel {
  RadioModelKind kind = RadioModelKind::ideal;
  WssParams wss;                            ///< used when kind == wss
  SubtParams subt;                          ///< used when kind == subt
  std::int64_t max_datagram_bytes = 65536;  ///< larger datagrams are rejected by send()
};

/// The model called `name` ("ideal", "wss" or "subt") with its defaults. Throws Error naming
/// the accepted names for any other.
RadioModel radio_model(std::string_view name);

/// The name of a model kind ("ideal", "wss", "subt").
std::string_view radio_model_name(RadioModelKind kind);

/// Sets the parameter `key` of the model's own kind (wss: p0_dbm, d0_m, n, wall_loss_db,
/// max_walls, cutoff_dbm; subt: l0_db, n, sigma_db, tx_power_dbm, noise_floor_dbm,
/// capacity_bps, max_range_m; every kind: max_datagram_bytes). Returns an error text for an
/// unknown key or a non-integer count; values are otherwise checked by validate_radio_model.
std::optional<std::string> set_radio_parameter(RadioModel& model, std::string_view key, double value);

/// Every impossible parameter of the model's kind, one message each, naming the parameter
/// as `radio.<kind>.<key>` and the value given (empty when the model is usable).
std::vector<std::string> validate_radio_model(const RadioModel& model);

/// Received power (dBm) between two radios `distance_m` apart with `walls` walls between
/// them and `shadowing_db` added (a draw of link_shadowing_db, or 0). ideal: +inf. wss:
/// distances below d0 count as d0 (the reference power is the strongest the model gives);
/// negative wall counts count as 0. subt: walls are ignored; distances below 1 m count as
/// 1 m (SubT's own model takes log10 of any range, which exceeds the transmit power below
/// 1 m and is infinite at 0); beyond max_range_m the power is −inf. A NaN distance gives NaN.
double received_power_dbm(const RadioModel& model, double distance_m, int walls, double shadowing_db = 0.0);

/// The weakest received power that links (dBm): wss cutoff, subt noise floor, ideal −inf.
double link_threshold_dbm(const RadioModel& model);

/// True when the model draws shadowing (subt with sigma_db > 0).
bool has_shadowing(const RadioModel& model);

/// The shadowing (dB) of the link between radios `id_a` and `id_b` at link update number
/// `update_index`: a normal draw with the model's sigma from a stream derived from (seed,
/// the unordered pair of ids, update_index), so (a, b) and (b, a) share it and the value
/// depends on nothing else. 0 for models without shadowing.
double link_shadowing_db(const RadioModel& model, std::uint64_t seed, std::string_view id_a, std::string_view id_b,
                         std::uint64_t update_index);

}  // namespace rescuesim
