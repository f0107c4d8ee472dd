#pragma once
/// RadioNetwork: the radios of a mission (robots, base stations, dropped relays), the link
/// between every pair under one RadioModel, multi-hop routes, and datagrams queued by send()
/// and handed to inboxes by deliver(). No ROS and no Bus: callers move positions in and
/// datagrams out. World frame, metres, dBm; time advances only through deliver(dt).
///
/// Determinism: nodes, links, routes, queues and inboxes are ordered by node index and send
/// order; shadowing draws depend only on (seed, pair of ids, update number); wall counts do
/// not depend on the ray scene's thread count. Same inputs and seed → same links and drops.
/// Not thread-safe: one caller at a time.

#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/index.h"
#include "core/pose.h"
#include "core/sim_time.h"
#include "radio/radio_routes.h"
#include "radio/wall_count.h"
#include "world/radio_model.h"

namespace rescuesim {

/// What a radio is carried by.
enum class RadioNodeKind { robot, base, relay };

/// One radio.
struct RadioNode {
  std::string id;                             ///< unique name, e.g. "robot1", "base", "robot1/relay_1"
  RadioNodeKind kind = RadioNodeKind::robot;
  Vec3 p_W = Vec3::Zero();                    ///< antenna position, world frame (m)
  RadioNodeIndex owner;                       ///< relays: the node of the robot that dropped it
};

/// The link between two radios at the last update().
struct RadioLink {
  double distance_m = std::numeric_limits<double>::quiet_NaN();  ///< NaN when a position is not finite
  int walls = 0;                 ///< walls counted (wss only; at most max_walls)
  double shadowing_db = 0;       ///< subt's shadowing draw for this update (dB)
  double rssi_dbm = -std::numeric_limits<double>::infinity();  ///< received power (dBm); +inf for ideal
  double margin_db = -std::numeric_limits<double>::infinity(); ///< rssi − threshold (dB); NaN/negative = no link
  bool connected = false;        ///< margin_db >= 0
};

/// Destination of a datagram sent to every current neighbour of the sender.
inline constexpr RadioNodeIndex kRadioBroadcast{};

/// A delivered datagram.
struct Datagram {
  std::uint64_t seq = 0;            ///< network-wide send order, from 1
  RadioNodeIndex from;              ///< sender node
  RadioNodeIndex to = kRadioBroadcast;  ///< destination node, or kRadioBroadcast
  std::vector<std::uint8_t> bytes;  ///< payload
  std::vector<RadioNodeIndex> path;  ///< nodes it went through, sender first, receiver last
  SimTime sent;                     ///< network time at send()
  SimTime delivered;                ///< network time of the deliver() that handed it over

  /// Links crossed (1 = direct).
  int hops() const { return static_cast<int>(path.size()) - 1; }
};

/// Why a queued datagram did not arrive.
enum class RadioDropReason { no_route, capacity };

/// The answer of send(): accepted, or why not.
struct SendResult {
  bool accepted = false;
  std::uint64_t seq = 0;  ///< the datagram's number when accepted
  std::string reason;     ///< why it was rejected ("" when accepted)
};

/// The answer of add_relay(): the new node, or why there is none.
struct RelayResult {
  RadioNodeIndex node;
  std::string reason;
  bool ok() const { return node.valid(); }
};

/// A radio heard at the last update.
struct RadioNeighbour {
  RadioNodeIndex node;
  double rssi_dbm = 0;   ///< received power (dBm)
  double margin_db = 0;  ///< over the model's threshold (dB)
};

/// What a radio knows about itself: its link status and traffic counters.
struct RadioStatus {
  std::vector<RadioNeighbour> neighbours;  ///< connected nodes, by node index
  std::optional<int> hops_to_base;         ///< fewest hops on the route to the nearest base (0 for a base); none out of contact
  std::uint64_t bytes_sent = 0;            ///< payload bytes accepted by send() from this node
  std::uint64_t bytes_received = 0;        ///< payload bytes delivered to its inbox
  std::uint64_t bytes_dropped = 0;         ///< payload bytes of its datagrams that did not arrive (per lost copy)
  std::uint64_t bytes_forwarded = 0;       ///< payload bytes it relayed for others
  std::uint64_t datagrams_sent = 0;
  std::uint64_t datagrams_received = 0;
  std::uint64_t datagrams_dropped = 0;     ///< lost copies of its datagrams
};

/// Options of a network beyond its radio model.
struct RadioNetworkOptions {
  /// Relays each robot may drop; the network enforces it in add_relay (SubT gave 12).
  int relays_per_robot = 12;
};

/// The radios of one mission and the links between them. See the file comment.
class RadioNetwork {
 public:
  /// Throws Error listing every problem of validate_radio_model, or a negative relay budget.
  RadioNetwork(RadioModel model, std::uint64_t seed, RadioNetworkOptions options = {});

  /// Adds a radio and returns its node index (0, 1, ... in call order). Throws Error for an
  /// empty or duplicate id. Its links are "no link" until the next update().
  RadioNodeIndex add_node(std::string id, RadioNodeKind kind, const Vec3& p_W);

  /// Drops a relay of robot `owner` at p_W (id "<owner id>/relay_<k>"), if the robot has
  /// budget left. Fails with a reason for a node that is not a robot, an exhausted budget or
  /// a position that is not finite. Its links exist from the next update().
  RelayResult add_relay(RadioNodeIndex owner, const Vec3& p_W);
  /// Relays robot `owner` may still drop.
  int relays_left(RadioNodeIndex owner) const;

  int node_count() const { return static_cast<int>(nodes_.size()); }
  const RadioNode& node(RadioNodeIndex index) const;
  /// Every node's index, in order.
  IndexRange<RadioNodeTag> node_indices() const { return indices<RadioNodeTag>(nodes_.size()); }
  /// The node called `id`, if any.
  std::optional<RadioNodeIndex> find(std::string_view id) const;
  /// Moves a radio (taken into account at the next update()).
  void set_position(RadioNodeIndex index, const Vec3& p_W);

  /// Recomputes every link from the nodes' positions: distance, walls (wss, when `walls` is
  /// given; otherwise open space), shadowing (subt: a new draw per update), received power,
  /// margin, and the widest-path bottlenecks behind route(). The caller decides the rate
  /// (missions use 10 Hz). Cost: n(n−1)/2 wall counts in one batch of rays, plus O(n³) for
  /// the routes.
  void update(const WallCounter* walls = nullptr);
  /// Sets every node's position (positions.size() must equal node_count(), else Error), then update().
  void update(std::span<const Vec3> positions, const WallCounter* walls = nullptr);

  /// The link between two nodes at the last update (symmetric).
  const RadioLink& link(RadioNodeIndex a, RadioNodeIndex b) const;
  /// The route from `from` to `to` at the last update (see radio_routes.h): nodes from
  /// sender to receiver, empty when there is none.
  std::vector<RadioNodeIndex> route(RadioNodeIndex from, RadioNodeIndex to) const;

  /// Queues a datagram for the next deliver(); `to` a node or kRadioBroadcast (every current
  /// neighbour of the sender, one hop). Rejected with a reason for unknown nodes, sending to
  /// oneself, or more than the model's max_datagram_bytes.
  SendResult send(RadioNodeIndex from, RadioNodeIndex to, std::vector<std::uint8_t> bytes);

  /// Hands every queued datagram (in send order) to its destination's inbox along the
  /// current route, then advances the network clock by dt_s (s, finite and >= 0, else
  /// Error). A datagram without a route is dropped, not kept for later. subt: each hop is
  /// charged to the transmitter's sent bytes and the receiver's received bytes over the last
  /// second; a hop that would take either beyond capacity_bps/8 bytes drops the datagram
  /// there (the hops before it are still charged).
  void deliver(double dt_s);

  /// The datagrams delivered to `node` and not yet taken, in delivery order.
  const std::vector<Datagram>& inbox(RadioNodeIndex node) const;
  /// Empties `node`'s inbox and returns what was in it.
  std::vector<Datagram> take_inbox(RadioNodeIndex node);
  /// Drops the oldest datagrams of `node`'s inbox beyond the newest `keep`; returns how many went.
  std::size_t trim_inbox(RadioNodeIndex node, std::size_t keep);

  /// Neighbours, hops to base and counters of `node`.
  RadioStatus status(RadioNodeIndex node) const;

  /// Datagram copies dropped for `reason` since construction.
  std::uint64_t dropped(RadioDropReason reason) const;
  /// update() calls so far.
  std::uint64_t update_count() const { return updates_; }
  /// The network clock (sum of deliver()'s dt).
  SimTime now() const { return now_; }
  const RadioModel& model() const { return model_; }

 private:
  /// Bytes a radio moved in the last second (subt's capacity window).
  struct Window {
    std::deque<std::pair<std::int64_t, std::int64_t>> entries;  ///< (time ns, bytes)
    std::int64_t sum = 0;
  };
  struct Traffic {
    Window tx, rx;
    RadioStatus counters;  ///< only the counters are used
  };

  void check_node(RadioNodeIndex index, const char* where) const;
  bool fits(Window& w, std::int64_t bytes) const;
  void charge(Window& w, std::int64_t bytes) const;
  void drop(const Datagram& d, RadioDropReason reason);

  RadioModel model_;
  std::uint64_t seed_;
  RadioNetworkOptions options_;
  IndexedVector<RadioNodeTag, RadioNode> nodes_;
  IndexedVector<RadioNodeTag, int> relays_dropped_;  ///< per node (robots)
  std::vector<RadioLink> links_;              ///< n×n, row-major, for the n at the last update
  int linked_n_ = 0;                          ///< node count at the last update
  MarginTable margins_;
  std::vector<std::vector<double>> bottlenecks_;  ///< per source, at the last update
  std::vector<Datagram> queue_;
  IndexedVector<RadioNodeTag, std::vector<Datagram>> inboxes_;
  IndexedVector<RadioNodeTag, Traffic> traffic_;
  std::uint64_t next_seq_ = 1;
  std::uint64_t updates_ = 0;
  std::uint64_t dropped_no_route_ = 0;
  std::uint64_t dropped_capacity_ = 0;
  SimTime now_;
};

}  // namespace rescuesim
