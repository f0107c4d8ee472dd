#pragma once
/// copy_fields(from, to): copies a struct field by field through its field list, `visit_fields`,
/// the visitor protocol State uses (world/state.h: leaves, `group`, `items`). A memory saved
/// and restored this way keeps exactly what its list names: a field left out of the list goes
/// back to its default on restore, which a restore test then shows, instead of being carried
/// by a struct copy nobody checks (session snapshots use it for the built-in team's memory).
///
/// Both walks run the same visit_fields on the same type, so the leaves line up by position; a
/// sequence walked with `items` is resized to the source's length before its elements are.

#include <cstddef>
#include <vector>

namespace rescuesim {

namespace field_copy_detail {

/// First walk: the address of every leaf and sequence of the source, in list order.
struct Collect {
  std::vector<const void*> at;
  template <class L>
  void operator()(const char*, const L& leaf) {
    at.push_back(&leaf);
  }
  template <class F>
  void group(const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void items(const char*, const std::vector<E>& v, F&& f) {
    at.push_back(&v);
    for (const E& e : v) f(*this, e);
  }
};

/// Second walk: assigns each leaf of the destination from the source's leaf at the same position.
struct Assign {
  const std::vector<const void*>& from;
  std::size_t next = 0;
  template <class L>
  void operator()(const char*, L& leaf) {
    leaf = *static_cast<const L*>(from[next++]);
  }
  template <class F>
  void group(const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void items(const char*, std::vector<E>& v, F&& f) {
    v.resize(static_cast<const std::vector<E>*>(from[next++])->size());
    for (E& e : v) f(*this, e);
  }
};

/// Counts the leaves and sequences of a field list, not descending into sequences.
struct Count {
  std::size_t n = 0;
  template <class L>
  void operator()(const char*, const L&) {
    ++n;
  }
  template <class F>
  void group(const char*, F&& f) {
    f(*this);
  }
  template <class E, class F>
  void items(const char*, const std::vector<E>&, F&&) {
    ++n;
  }
};

}  // namespace field_copy_detail

/// Copies every field `visit_fields(T&, visitor)` lists from `from` to `to`; the rest of `to` is
/// left as it was.
template <class T>
void copy_fields(const T& from, T& to) {
  field_copy_detail::Collect c;
  visit_fields(from, c);
  field_copy_detail::Assign a{c.at};
  visit_fields(to, a);
}

/// The number of leaves and sequences `visit_fields` lists for one T (sequences counted once,
/// their elements not): what a test compares with T's member count.
template <class T>
std::size_t listed_fields(const T& value) {
  field_copy_detail::Count count;
  visit_fields(value, count);
  return count.n;
}

}  // namespace rescuesim
