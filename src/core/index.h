#pragma once
/// Typed indices: a robot, a victim and a radio node are each counted from 0, and a plain `int`
/// lets one be passed where another is meant (`sim.command_velocity(victim, ...)` compiled).
/// `Index<Tag>` is an int that only converts to and from itself: a RobotIndex is not a
/// VictimIndex, not an int and not a size_t, so a mixed-up index no longer compiles. It is the
/// idea of Drake's TypeSafeIndex<Tag> and of Box2D's b2BodyId, and what TopicId (bus/topic_id.h)
/// already does for topics. `IndexedVector<Tag, T>` is a std::vector addressed only by its
/// index type, for data kept one per robot (or victim, or radio node).
///
///   for (RobotIndex r : indices<RobotTag>(world.robots.size())) sim.command_velocity(r, twist);
///   IndexedVector<RobotTag, double> travelled(world.robots.size());
///   travelled[r] += step;          // travelled[3] does not compile
///
/// A default-constructed index is invalid (-1: "no robot"); `slot()` of an invalid index is a bug
/// and aborts (RS_DEMAND), so a missing robot is caught where it is used as a position.
#include <compare>
#include <cstddef>
#include <functional>
#include <iterator>
#include <limits>
#include <vector>

#include "core/error.h"

namespace rescuesim {

template <class Tag>
class Index {
 public:
  /// Invalid: no element.
  constexpr Index() = default;
  /// The element at `value`; -1 (or any negative value) is invalid.
  constexpr explicit Index(int value) : value_(value < 0 ? -1 : value) {}
  /// The element at a container position (checked: it must fit an int).
  static Index at(std::size_t slot) {
    RS_DEMAND(slot <= static_cast<std::size_t>(std::numeric_limits<int>::max()), "an index beyond int");
    return Index(static_cast<int>(slot));
  }

  constexpr bool valid() const { return value_ >= 0; }
  /// The number, -1 when invalid (for messages, JSON and bindings that speak ints).
  constexpr int value() const { return value_; }
  /// The container position; an invalid index aborts (a bug: check valid() first).
  std::size_t slot() const {
    RS_DEMAND(valid(), "an invalid index used as a position");
    return static_cast<std::size_t>(value_);
  }

  constexpr Index& operator++() {
    ++value_;
    return *this;
  }
  constexpr Index operator++(int) {
    Index before = *this;
    ++value_;
    return before;
  }
  friend constexpr auto operator<=>(Index, Index) = default;
  /// Prints the number (-1 when invalid), for test failure messages.
  template <class Stream>
  friend auto operator<<(Stream& os, Index i) -> decltype(os << 0) {
    return os << i.value_;
  }

 private:
  int value_ = -1;
};

/// The indices 0 .. count-1 in order, for `for (RobotIndex r : indices<RobotTag>(n))`.
template <class Tag>
class IndexRange {
 public:
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Index<Tag>;
    using difference_type = std::ptrdiff_t;
    using pointer = const Index<Tag>*;
    using reference = Index<Tag>;
    constexpr iterator() = default;
    constexpr explicit iterator(int i) : i_(i) {}
    constexpr Index<Tag> operator*() const { return i_; }
    constexpr iterator& operator++() {
      ++i_;
      return *this;
    }
    constexpr iterator operator++(int) { return iterator((i_++).value()); }
    friend constexpr bool operator==(iterator, iterator) = default;

   private:
    Index<Tag> i_{0};
  };
  constexpr explicit IndexRange(int count) : count_(count) {}
  constexpr iterator begin() const { return iterator(0); }
  constexpr iterator end() const { return iterator(count_); }
  constexpr std::size_t size() const { return static_cast<std::size_t>(count_); }

 private:
  int count_ = 0;
};

template <class Tag>
IndexRange<Tag> indices(std::size_t count) {
  RS_DEMAND(count <= static_cast<std::size_t>(std::numeric_limits<int>::max()), "more elements than an int index counts");
  return IndexRange<Tag>(static_cast<int>(count));
}

/// A std::vector whose elements are addressed by Index<Tag> only. Everything else (size,
/// iteration, push_back, resize, ...) is the vector's; `vector()` gives the vector itself to code
/// that takes one (field visitors, algorithms).
template <class Tag, class T>
class IndexedVector {
 public:
  using value_type = T;
  using index_type = Index<Tag>;
  using reference = typename std::vector<T>::reference;  // a proxy for bool, as in std::vector
  using const_reference = typename std::vector<T>::const_reference;
  using iterator = typename std::vector<T>::iterator;
  using const_iterator = typename std::vector<T>::const_iterator;

  IndexedVector() = default;
  explicit IndexedVector(std::size_t count, const T& value = T()) : items_(count, value) {}

  reference operator[](Index<Tag> i) { return items_[i.slot()]; }
  const_reference operator[](Index<Tag> i) const { return items_[i.slot()]; }
  /// Bounds-checked access (std::out_of_range beyond the end, like std::vector::at).
  reference at(Index<Tag> i) { return items_.at(i.slot()); }
  const_reference at(Index<Tag> i) const { return items_.at(i.slot()); }
  /// Whether `i` names an element.
  bool contains(Index<Tag> i) const { return i.valid() && i.slot() < items_.size(); }

  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  IndexRange<Tag> indices() const { return rescuesim::indices<Tag>(items_.size()); }
  /// The index the next push_back gets.
  Index<Tag> next_index() const { return Index<Tag>::at(items_.size()); }

  iterator begin() { return items_.begin(); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin(); }
  const_iterator end() const { return items_.end(); }
  reference back() { return items_.back(); }
  const_reference back() const { return items_.back(); }

  void push_back(const T& item) { items_.push_back(item); }
  void push_back(T&& item) { items_.push_back(std::move(item)); }
  template <class... Args>
  reference emplace_back(Args&&... args) {
    return items_.emplace_back(std::forward<Args>(args)...);
  }
  void resize(std::size_t count) { items_.resize(count); }
  void resize(std::size_t count, const T& value) { items_.resize(count, value); }
  void clear() { items_.clear(); }
  /// Removes element `i`; the ones after it move down one index.
  void erase(Index<Tag> i) { items_.erase(items_.begin() + static_cast<std::ptrdiff_t>(i.slot())); }

  std::vector<T>& vector() { return items_; }
  const std::vector<T>& vector() const { return items_; }

 private:
  std::vector<T> items_;
};

/// The indices of the simulation: a robot of World::robots (and State::robots), a victim of
/// World::victims, a node of a mission's radio network (robots first, then bases, then relays).
using RobotIndex = Index<struct RobotTag>;
using VictimIndex = Index<struct VictimTag>;
using RadioNodeIndex = Index<struct RadioNodeTag>;

}  // namespace rescuesim

template <class Tag>
struct std::hash<rescuesim::Index<Tag>> {
  std::size_t operator()(rescuesim::Index<Tag> i) const noexcept { return std::hash<int>()(i.value()); }
};
