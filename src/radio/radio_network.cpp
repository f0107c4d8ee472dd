#include "radio/radio_network.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim {

namespace {

constexpr std::int64_t kWindowNs = 1'000'000'000;

bool finite3(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

}  // namespace

RadioNetwork::RadioNetwork(RadioModel model, std::uint64_t seed, RadioNetworkOptions options)
    : model_(std::move(model)), seed_(seed), options_(options) {
  std::vector<std::string> errors = validate_radio_model(model_);
  if (options_.relays_per_robot < 0) {
    errors.push_back(fmt::format("radio.relays_per_robot: must be >= 0 (got {})", options_.relays_per_robot));
  }
  if (!errors.empty()) {
    std::string text = "RadioNetwork: invalid radio parameters:";
    for (const std::string& e : errors) text += "\n  " + e;
    throw Error(text);
  }
}

void RadioNetwork::check_node(RadioNodeIndex index, const char* where) const {
  if (!nodes_.contains(index)) {
    throw Error(fmt::format("RadioNetwork::{}: no node {} (the network has {})", where, index.value(), node_count()));
  }
}

RadioNodeIndex RadioNetwork::add_node(std::string id, RadioNodeKind kind, const Vec3& p_W) {
  if (id.empty()) throw Error("RadioNetwork::add_node: empty node id");
  if (find(id)) throw Error(fmt::format("RadioNetwork::add_node: duplicate node id '{}'", id));
  const RadioNodeIndex added = nodes_.next_index();
  nodes_.push_back({std::move(id), kind, p_W, {}});
  relays_dropped_.push_back(0);
  inboxes_.emplace_back();
  traffic_.emplace_back();
  return added;
}

RelayResult RadioNetwork::add_relay(RadioNodeIndex owner, const Vec3& p_W) {
  if (!nodes_.contains(owner)) return {{}, fmt::format("no node {} to drop a relay", owner.value())};
  const RadioNode& robot = nodes_[owner];
  if (robot.kind != RadioNodeKind::robot) return {{}, fmt::format("'{}' is not a robot: only robots drop relays", robot.id)};
  if (relays_left(owner) <= 0) {
    return {{}, fmt::format("'{}' has no relays left (budget {})", robot.id, options_.relays_per_robot)};
  }
  if (!finite3(p_W)) return {{}, fmt::format("relay position of '{}' is not finite", robot.id)};
  const int k = ++relays_dropped_[owner];
  const RadioNodeIndex node = add_node(fmt::format("{}/relay_{}", robot.id, k), RadioNodeKind::relay, p_W);
  nodes_[node].owner = owner;
  return {node, ""};
}

int RadioNetwork::relays_left(RadioNodeIndex owner) const {
  check_node(owner, "relays_left");
  if (nodes_[owner].kind != RadioNodeKind::robot) return 0;
  return options_.relays_per_robot - relays_dropped_[owner];
}

const RadioNode& RadioNetwork::node(RadioNodeIndex index) const {
  check_node(index, "node");
  return nodes_[index];
}

std::optional<RadioNodeIndex> RadioNetwork::find(std::string_view id) const {
  for (RadioNodeIndex i : nodes_.indices()) {
    if (nodes_[i].id == id) return i;
  }
  return std::nullopt;
}

void RadioNetwork::set_position(RadioNodeIndex index, const Vec3& p_W) {
  check_node(index, "set_position");
  nodes_[index].p_W = p_W;
}

void RadioNetwork::update(std::span<const Vec3> positions, const WallCounter* walls) {
  if (static_cast<int>(positions.size()) != node_count()) {
    throw Error(fmt::format("RadioNetwork::update: {} positions for {} nodes", positions.size(), node_count()));
  }
  for (RadioNodeIndex i : nodes_.indices()) nodes_[i].p_W = positions[i.slot()];
  update(walls);
}

void RadioNetwork::update(const WallCounter* walls) {
  const int n = node_count();
  const auto un = static_cast<std::size_t>(n);
  ++updates_;
  linked_n_ = n;
  links_.assign(un * un, RadioLink{});

  // the pairs a < b in order; wall counts for all of them in one batch (wss only)
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(un * (un - (n > 0 ? 1 : 0)) / 2);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) pairs.emplace_back(a, b);
  }
  std::vector<int> wall_counts(pairs.size(), 0);
  if (walls != nullptr && model_.kind == RadioModelKind::wss && model_.wss.max_walls > 0) {
    std::vector<RadioSegment> segments;
    segments.reserve(pairs.size());
    for (const auto& [a, b] : pairs) segments.push_back({nodes_[RadioNodeIndex(a)].p_W, nodes_[RadioNodeIndex(b)].p_W});
    walls->count(segments, wall_counts, model_.wss.max_walls);
  }

  // each pair's link budget, mirrored
  const double threshold = link_threshold_dbm(model_);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [a, b] = pairs[k];
    const RadioNode& na = nodes_[RadioNodeIndex(a)];
    const RadioNode& nb = nodes_[RadioNodeIndex(b)];
    RadioLink l;
    if (finite3(na.p_W) && finite3(nb.p_W)) {
      l.distance_m = (nb.p_W - na.p_W).norm();
      l.walls = wall_counts[k];
      l.shadowing_db = link_shadowing_db(model_, seed_, na.id, nb.id, updates_);
      l.rssi_dbm = received_power_dbm(model_, l.distance_m, l.walls, l.shadowing_db);
      l.margin_db = l.rssi_dbm - threshold;
      if (model_.kind == RadioModelKind::ideal) l.margin_db = std::numeric_limits<double>::infinity();
      l.connected = l.margin_db >= 0.0;
    }
    links_[static_cast<std::size_t>(a) * un + static_cast<std::size_t>(b)] = l;
    links_[static_cast<std::size_t>(b) * un + static_cast<std::size_t>(a)] = l;
  }

  // the widest-path bottlenecks from every node, for route()
  margins_.n = n;
  margins_.margin_db.assign(un * un, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].connected) margins_.margin_db[i] = links_[i].margin_db;
  }
  bottlenecks_.clear();
  for (int s = 0; s < n; ++s) bottlenecks_.push_back(widest_bottlenecks(margins_, s));
}

const RadioLink& RadioNetwork::link(RadioNodeIndex a, RadioNodeIndex b) const {
  static const RadioLink kNoLink;
  check_node(a, "link");
  check_node(b, "link");
  if (a.value() >= linked_n_ || b.value() >= linked_n_ || a == b) return kNoLink;
  return links_[a.slot() * static_cast<std::size_t>(linked_n_) + b.slot()];
}

std::vector<RadioNodeIndex> RadioNetwork::route(RadioNodeIndex from, RadioNodeIndex to) const {
  check_node(from, "route");
  check_node(to, "route");
  if (from == to) return {from};
  if (from.value() >= linked_n_ || to.value() >= linked_n_) return {};
  // the route search works on plain node numbers (radio_routes.h: a table of margins)
  std::vector<RadioNodeIndex> out;
  for (int v : widest_route(margins_, bottlenecks_[from.slot()], from.value(), to.value())) out.emplace_back(v);
  return out;
}

SendResult RadioNetwork::send(RadioNodeIndex from, RadioNodeIndex to, std::vector<std::uint8_t> bytes) {
  if (!nodes_.contains(from)) return {false, 0, fmt::format("unknown sender node {}", from.value())};
  if (to != kRadioBroadcast && !nodes_.contains(to)) return {false, 0, fmt::format("unknown destination node {}", to.value())};
  if (to == from) return {false, 0, "the destination is the sender"};
  const auto size = static_cast<std::int64_t>(bytes.size());
  if (size > model_.max_datagram_bytes) {
    return {false, 0, fmt::format("datagram of {} bytes exceeds the {}-byte limit (max_datagram_bytes)", size, model_.max_datagram_bytes)};
  }
  Datagram d;
  d.seq = next_seq_++;
  d.from = from;
  d.to = to;
  d.bytes = std::move(bytes);
  d.sent = now_;
  RadioStatus& c = traffic_[from].counters;
  c.bytes_sent += static_cast<std::uint64_t>(size);
  ++c.datagrams_sent;
  queue_.push_back(std::move(d));
  return {true, queue_.back().seq, ""};
}

bool RadioNetwork::fits(Window& w, std::int64_t bytes) const {
  if (model_.kind != RadioModelKind::subt) return true;
  // forget what left the one-second window, then compare with the capacity in bytes
  while (!w.entries.empty() && w.entries.front().first <= now_.ns - kWindowNs) {
    w.sum -= w.entries.front().second;
    w.entries.pop_front();
  }
  return static_cast<double>(w.sum + bytes) <= model_.subt.capacity_bps / 8.0;
}

void RadioNetwork::charge(Window& w, std::int64_t bytes) const {
  if (model_.kind != RadioModelKind::subt) return;
  w.entries.emplace_back(now_.ns, bytes);
  w.sum += bytes;
}

void RadioNetwork::drop(const Datagram& d, RadioDropReason reason) {
  RadioStatus& c = traffic_[d.from].counters;
  c.bytes_dropped += d.bytes.size();
  ++c.datagrams_dropped;
  (reason == RadioDropReason::no_route ? dropped_no_route_ : dropped_capacity_) += 1;
}

void RadioNetwork::deliver(double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s >= 0)) throw Error(fmt::format("RadioNetwork::deliver: dt must be finite and >= 0 (got {})", dt_s));
  std::vector<Datagram> queue = std::move(queue_);
  queue_.clear();
  auto arrive = [&](Datagram d) {
    RadioStatus& c = traffic_[d.path.back()].counters;
    c.bytes_received += d.bytes.size();
    ++c.datagrams_received;
    d.delivered = now_;
    inboxes_[d.path.back()].push_back(std::move(d));
  };
  for (Datagram& d : queue) {
    const auto size = static_cast<std::int64_t>(d.bytes.size());
    if (d.to == kRadioBroadcast) {
      // one transmission heard by every current neighbour that has room to receive it
      std::vector<RadioNodeIndex> heard;
      for (RadioNodeIndex v : indices<RadioNodeTag>(static_cast<std::size_t>(linked_n_))) {
        if (d.from.value() < linked_n_ && link(d.from, v).connected) heard.push_back(v);
      }
      if (heard.empty()) {
        drop(d, RadioDropReason::no_route);
        continue;
      }
      Traffic& tx = traffic_[d.from];
      if (!fits(tx.tx, size)) {
        for (std::size_t i = 0; i < heard.size(); ++i) drop(d, RadioDropReason::capacity);
        continue;
      }
      charge(tx.tx, size);
      for (RadioNodeIndex v : heard) {
        Traffic& rx = traffic_[v];
        if (!fits(rx.rx, size)) {
          drop(d, RadioDropReason::capacity);
          continue;
        }
        charge(rx.rx, size);
        Datagram copy = d;
        copy.path = {d.from, v};
        arrive(std::move(copy));
      }
      continue;
    }

    // unicast along the route of the last update, hop by hop
    d.path = route(d.from, d.to);
    if (d.path.size() < 2) {
      drop(d, RadioDropReason::no_route);
      continue;
    }
    bool lost = false;
    for (std::size_t h = 0; h + 1 < d.path.size(); ++h) {
      Traffic& tx = traffic_[d.path[h]];
      Traffic& rx = traffic_[d.path[h + 1]];
      if (!fits(tx.tx, size) || !fits(rx.rx, size)) {
        lost = true;
        break;
      }
      charge(tx.tx, size);
      charge(rx.rx, size);
      if (h > 0) tx.counters.bytes_forwarded += static_cast<std::uint64_t>(size);
    }
    if (lost) {
      drop(d, RadioDropReason::capacity);
      continue;
    }
    arrive(std::move(d));
  }
  now_.ns += SimTime::from_seconds(dt_s).ns;
}

const std::vector<Datagram>& RadioNetwork::inbox(RadioNodeIndex node) const {
  check_node(node, "inbox");
  return inboxes_[node];
}

std::vector<Datagram> RadioNetwork::take_inbox(RadioNodeIndex node) {
  check_node(node, "take_inbox");
  std::vector<Datagram> out = std::move(inboxes_[node]);
  inboxes_[node].clear();
  return out;
}

std::size_t RadioNetwork::trim_inbox(RadioNodeIndex node, std::size_t keep) {
  check_node(node, "trim_inbox");
  auto& inbox = inboxes_[node];
  if (inbox.size() <= keep) return 0;
  const std::size_t n = inbox.size() - keep;
  inbox.erase(inbox.begin(), inbox.begin() + static_cast<std::ptrdiff_t>(n));
  return n;
}

RadioStatus RadioNetwork::status(RadioNodeIndex node) const {
  check_node(node, "status");
  RadioStatus s = traffic_[node].counters;
  s.neighbours.clear();
  s.hops_to_base.reset();
  if (node.value() < linked_n_) {
    for (RadioNodeIndex v : indices<RadioNodeTag>(static_cast<std::size_t>(linked_n_))) {
      const RadioLink& l = link(node, v);
      if (l.connected) s.neighbours.push_back({v, l.rssi_dbm, l.margin_db});
    }
  }
  // the fewest hops to any base along its widest route
  for (RadioNodeIndex b : nodes_.indices()) {
    if (nodes_[b].kind != RadioNodeKind::base) continue;
    const std::vector<RadioNodeIndex> r = route(node, b);
    if (r.empty()) continue;
    const int hops = static_cast<int>(r.size()) - 1;
    if (!s.hops_to_base || hops < *s.hops_to_base) s.hops_to_base = hops;
  }
  return s;
}

std::uint64_t RadioNetwork::dropped(RadioDropReason reason) const {
  return reason == RadioDropReason::no_route ? dropped_no_route_ : dropped_capacity_;
}

}  // namespace rescuesim
