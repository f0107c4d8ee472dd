/// SVG path data (`d` attribute): M L H V C S Q T A Z, absolute and relative, with implicit
/// repeats, flattened into world-space polylines by svg_flatten.cpp.

#include <cmath>
#include <string>

#include "import/svg/svg_detail.h"
#include "import/svg/svg_parse.h"

namespace rescuesim::svg {

namespace {

using detail::quote;

/// Most points one path may flatten to; a guard against hostile files, far above real maps.
constexpr std::size_t kMaxPathPoints = std::size_t(1) << 22;

bool is_command(char c) {
  switch (detail::to_lower(c)) {
    case 'm': case 'l': case 'h': case 'v': case 'c': case 's':
    case 'q': case 't': case 'a': case 'z':
      return true;
    default:
      return false;
  }
}

bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/// The parser's state while it walks one `d` attribute.
class PathParser {
 public:
  PathParser(std::string_view d, const Eigen::Affine2d& to_world, double tolerance)
      : s_(d), f_{to_world, tolerance} {}

  std::vector<Subpath> run() {
    detail::skip_space(s_, pos_);
    if (pos_ == s_.size()) return {};
    if (s_[pos_] != 'M' && s_[pos_] != 'm')
      throw ParseError("path data must start with a moveto ('M' or 'm'), found " + quote(s_, pos_), pos_);

    while (true) {
      // a command letter, or more numbers repeating the previous command
      detail::skip_space(s_, pos_);
      const std::size_t comma = pos_;
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        detail::skip_space(s_, pos_);
      }
      if (pos_ == s_.size()) break;
      const std::size_t offset = pos_;
      const char c = s_[pos_];
      if (is_letter(c)) {
        if (comma != pos_ && s_[comma] == ',') throw ParseError("unexpected ',' before a path command", comma);
        if (!is_command(c)) throw ParseError("unknown path command '" + std::string(1, c) + "'", pos_);
        command_ = c;
        ++pos_;
      } else if (detail::starts_number(s_, pos_)) {
        if (command_ == 'Z' || command_ == 'z')
          throw ParseError("expected a path command after 'Z', found " + quote(s_, pos_), pos_);
        // extra coordinate pairs after a moveto are linetos
        if (command_ == 'M') command_ = 'L';
        if (command_ == 'm') command_ = 'l';
      } else {
        throw ParseError("expected a path command, found " + quote(s_, pos_), pos_);
      }
      execute(offset);
    }
    finish(false);
    return std::move(result_);
  }

 private:
  /// Reads one number argument of the current command.
  double number() {
    std::size_t p = pos_;
    detail::skip_space(s_, p);
    if (p < s_.size() && s_[p] == ',') {
      ++p;
      detail::skip_space(s_, p);
    }
    // spelled infinities and NaNs get read_number's message; anything else non-numeric gets ours
    std::string word;
    for (char c : s_.substr(p, 3)) word += detail::to_lower(c);
    if (!detail::starts_number(s_, p) && word != "inf" && word != "nan")
      throw ParseError("expected a number after '" + std::string(1, command_) + "', found " + quote(s_, p), p);
    return read_number(s_, pos_);
  }

  /// A coordinate pair, made absolute.
  Vec2 point(bool relative) {
    const double x = number();
    const double y = number();
    return relative ? Vec2(cur_ + Vec2(x, y)) : Vec2(x, y);
  }

  /// An arc flag: the single character 0 or 1, which needs no separator after it.
  bool flag() {
    detail::skip_space(s_, pos_);
    if (pos_ < s_.size() && s_[pos_] == ',') {
      ++pos_;
      detail::skip_space(s_, pos_);
    }
    if (pos_ < s_.size() && (s_[pos_] == '0' || s_[pos_] == '1')) return s_[pos_++] == '1';
    throw ParseError("expected an arc flag (0 or 1) after '" + std::string(1, command_) + "', found " +
                         quote(s_, pos_),
                     pos_);
  }

  /// Starts a subpath at the current point unless one is open (drawing right after Z).
  std::vector<Vec2>& out() {
    if (!open_) {
      current_ = Subpath{};
      f_.point(current_.points, cur_);
      open_ = true;
    }
    return current_.points;
  }

  /// Ends the open subpath; one that never left its start point produces nothing.
  void finish(bool closed) {
    if (!open_) return;
    open_ = false;
    auto& pts = current_.points;
    if (closed && pts.size() > 1 && detail::same_point(pts.front(), pts.back())) pts.pop_back();
    if (pts.size() < 2) return;
    current_.closed = closed;
    total_points_ += pts.size();
    result_.push_back(std::move(current_));
  }

  /// Reads the arguments of one command and draws it.
  void execute(std::size_t offset) {
    const bool rel = command_ >= 'a' && command_ <= 'z';
    const char kind = char(rel ? command_ - 'a' + 'A' : command_);
    std::size_t before = open_ ? current_.points.size() : 0;
    switch (kind) {
      case 'M': {
        const Vec2 p = point(rel);
        finish(false);
        cur_ = start_ = p;
        out();
        before = 0;
        break;
      }
      case 'Z':
        finish(true);
        cur_ = start_;
        break;
      case 'L': {
        const Vec2 p = point(rel);
        f_.point(out(), p);
        cur_ = p;
        break;
      }
      case 'H': {
        const double x = number();
        const Vec2 p(rel ? cur_.x() + x : x, cur_.y());
        f_.point(out(), p);
        cur_ = p;
        break;
      }
      case 'V': {
        const double y = number();
        const Vec2 p(cur_.x(), rel ? cur_.y() + y : y);
        f_.point(out(), p);
        cur_ = p;
        break;
      }
      case 'C':
      case 'S': {
        // S reflects the previous cubic's second control point, if there was a cubic
        const bool follows_cubic = previous_ == 'C' || previous_ == 'S';
        const Vec2 c0 = kind == 'C' ? point(rel) : follows_cubic ? Vec2(2.0 * cur_ - cubic_control_) : cur_;
        const Vec2 c1 = point(rel);
        const Vec2 p = point(rel);
        f_.cubic(out(), cur_, c0, c1, p);
        cubic_control_ = c1;
        cur_ = p;
        break;
      }
      case 'Q':
      case 'T': {
        // T reflects the previous quadratic's control point, if there was a quadratic
        const bool follows_quad = previous_ == 'Q' || previous_ == 'T';
        const Vec2 c = kind == 'Q' ? point(rel) : follows_quad ? Vec2(2.0 * cur_ - quad_control_) : cur_;
        const Vec2 p = point(rel);
        f_.quad(out(), cur_, c, p);
        quad_control_ = c;
        cur_ = p;
        break;
      }
      case 'A': {
        const double rx = number(), ry = number(), phi = number();
        const bool large = flag(), sweep = flag();
        const Vec2 p = point(rel);
        f_.arc(out(), cur_, rx, ry, phi, large, sweep, p);
        cur_ = p;
        break;
      }
    }
    previous_ = kind;
    check(offset, before);
  }

  /// Rejects coordinates that overflowed through the transform and runaway point counts.
  void check(std::size_t offset, std::size_t before) {
    if (!open_) return;
    const auto& pts = current_.points;
    for (std::size_t i = before; i < pts.size(); ++i)
      if (!pts[i].allFinite()) throw ParseError("path coordinates are not finite after the transform", offset);
    if (total_points_ + pts.size() > kMaxPathPoints)
      throw ParseError("path flattens to more than " + std::to_string(kMaxPathPoints) +
                           " points; simplify it or raise the curve tolerance",
                       offset);
  }

  std::string_view s_;
  detail::Flattener f_;
  std::size_t pos_ = 0;
  char command_ = 0;    ///< the current command letter as written
  char previous_ = 0;   ///< upper-case kind of the previous command, for S/T reflection
  Vec2 cur_ = Vec2::Zero();
  Vec2 start_ = Vec2::Zero();
  Vec2 cubic_control_ = Vec2::Zero();
  Vec2 quad_control_ = Vec2::Zero();
  bool open_ = false;
  Subpath current_;
  std::size_t total_points_ = 0;
  std::vector<Subpath> result_;
};

}  // namespace

std::vector<Subpath> parse_path(std::string_view d, const Eigen::Affine2d& to_world, double tolerance) {
  return PathParser(d, to_world, tolerance).run();
}

}  // namespace rescuesim::svg
