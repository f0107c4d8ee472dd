// rescuesim snapshot and rescuesim view as a user and CI meet them: the Fig. 2 composite has the
// documented size and something in every panel; the window, under xvfb-run, shows the main view
// and four live sensor panels in its screenshot; without a display it says what to do instead.
//
// The app tests link only the world module, so images are decoded by netpbm's pngtopnm
// (installed with the other dependencies by scripts/install-deps.sh).

#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "support/command.h"

namespace rescuesim {
namespace {

using testing::rescuesim;
using testing::run_command;
using testing::slurp;
using testing::temp_dir;

/// An 8-bit RGB image.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

/// Width and height from a PNG's IHDR chunk (0 × 0 when it is not a PNG).
std::pair<int, int> png_size(const std::string& bytes) {
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<std::uint8_t>(bytes[at + i]);
    return static_cast<int>(v);
  };
  return {be32(16), be32(20)};
}

/// Decodes a PNG through `pngtopnm` into RGB (binary PPM, maxval 255).
Image decode(const std::filesystem::path& png) {
  const auto ppm = png.string() + ".ppm";
  // a subshell, so that run_command's own redirection of stdout does not replace ours
  const auto r = run_command("(pngtopnm '" + png.string() + "' > '" + ppm + "')");
  Image img;
  if (r.exit_code != 0) {
    ADD_FAILURE() << "pngtopnm failed on " << png << ": " << r.err;
    return img;
  }
  const std::string data = slurp(ppm);
  std::filesystem::remove(ppm);
  // header: "P6", width, height, maxval, separated by whitespace, then one whitespace byte
  std::size_t pos = 0;
  auto token = [&] {
    while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    const std::size_t start = pos;
    while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    return data.substr(start, pos - start);
  };
  if (token() != "P6") {
    ADD_FAILURE() << png << " did not decode to an RGB PPM";
    return img;
  }
  img.width = std::stoi(token());
  img.height = std::stoi(token());
  if (token() != "255") ADD_FAILURE() << "unexpected PPM maxval";
  ++pos;
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height * 3;
  if (data.size() < pos + n) {
    ADD_FAILURE() << "truncated PPM";
    return img;
  }
  img.rgb.assign(data.begin() + static_cast<std::ptrdiff_t>(pos), data.begin() + static_cast<std::ptrdiff_t>(pos + n));
  return img;
}

/// A region to check, in pixels.
struct Region {
  const char* name;
  int x, y, w, h;
};

/// Standard deviation of the luminance over the middle 80 % of a region (the part well inside
/// its frame): a blank or flat panel has almost none.
double luminance_stddev(const Image& img, const Region& r) {
  const int x0 = r.x + r.w / 10, x1 = r.x + r.w - r.w / 10, y0 = r.y + r.h / 10, y1 = r.y + r.h - r.h / 10;
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 3;
      const double l = 0.2126 * img.rgb[i] + 0.7152 * img.rgb[i + 1] + 0.0722 * img.rgb[i + 2];
      sum += l;
      sum2 += l * l;
      ++n;
    }
  }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

/// Mean colour over the middle 80 % of a region.
std::array<double, 3> mean_colour(const Image& img, const Region& r) {
  std::array<double, 3> m{0, 0, 0};
  int n = 0;
  for (int y = r.y + r.h / 10; y < r.y + r.h - r.h / 10; ++y) {
    for (int x = r.x + r.w / 10; x < r.x + r.w - r.w / 10; ++x) {
      for (int k = 0; k < 3; ++k) m[static_cast<std::size_t>(k)] += img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3 + k];
      ++n;
    }
  }
  for (double& v : m) v /= n;
  return m;
}

/// Fraction of a region's pixels in the warm end of the iron palette (orange to white: red
/// above 200), i.e. at least about 30 C in the default 15..40 C window.
double warm_fraction(const Image& img, const Region& r) {
  int warm = 0;
  for (int y = r.y; y < r.y + r.h; ++y) {
    for (int x = r.x; x < r.x + r.w; ++x) warm += img.rgb[(static_cast<std::size_t>(y) * img.width + x) * 3] > 200;
  }
  return static_cast<double>(warm) / (r.w * r.h);
}

/// A 6 x 4 m room: the robot at the west end facing east, a victim lying 2 m ahead of it, a
/// block of rubble and a short wall; no controller, so the robot stays where it starts.
std::filesystem::path write_victim_room(const std::filesystem::path& dir) {
  testing::write_text(dir / "room.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 600 400">
  <rect x="0" y="0" width="600" height="400" fill="none" stroke="#000" stroke-width="5"/>
  <line x1="420" y1="0" x2="420" y2="140" stroke="#000" stroke-width="5"/>
  <rect x="470" y="250" width="60" height="60" fill="#ff8c00" data-height="0.25"/>
  <rect id="victim" x="260" y="190" width="120" height="40" fill="#1f77b4" data-posture="lying"/>
  <circle id="robot" cx="80" cy="200" r="25" fill="#2ca02c"/>
  <line x1="80" y1="200" x2="140" y2="200" stroke="#2ca02c" stroke-width="5"/>
</svg>
)");
  testing::write_text(dir / "room.yaml",
                      "name: victim-room\nseed: 1\nworld:\n  svg: room.svg\nrobots:\n  - name: robot\n    controller: none\n");
  return dir / "room.yaml";
}

/// Every region of `img` shows something: its luminance varies by more than a few levels.
void expect_content(const Image& img, const std::vector<Region>& regions) {
  for (const Region& r : regions) {
    ASSERT_LE(r.x + r.w, img.width) << r.name;
    ASSERT_LE(r.y + r.h, img.height) << r.name;
    EXPECT_GT(luminance_stddev(img, r), 6.0) << r.name << " looks blank";
  }
}

// figure regions at the default width 1600 (src/app/figure.h, rescuesim snapshot --help)
const Region kFigMain{"main view", 20, 53, 896, 548};
const Region kFigLaser{"laser", 928, 53, 320, 240};
const Region kFigColour{"colour camera", 1260, 53, 320, 240};
const Region kFigDepth{"depth camera", 928, 361, 320, 240};
const Region kFigThermal{"thermal camera", 1260, 361, 320, 240};

TEST(ViewSnapshot, SnapshotOfTheDefaultScenarioHasTheDocumentedSizeAndPanels) {
  const auto dir = temp_dir("snapshot");
  const auto png = dir / "fig.png";
  // at 2 s the explorer's camera swing (the mast, +-60 degrees every 4 s) is back at ahead,
  // looking down a corridor: every panel shows something, and no victim is in view
  const auto r = rescuesim("snapshot --time 2 --out '" + png.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1600x669"), std::string::npos) << r.out;
  EXPECT_EQ(png_size(slurp(png)), std::make_pair(1600, 669));
  const Image img = decode(png);
  ASSERT_EQ(img.width, 1600);
  ASSERT_EQ(img.height, 669);
  expect_content(img, {kFigMain, kFigLaser, kFigColour, kFigDepth, {"title", 20, 20, 600, 21}});
  // no victim in view: the thermal camera sees the 20 C ambient, near the cool
  // (blue-purple) end of its 15..40 C window, and nothing warm
  const auto thermal = mean_colour(img, kFigThermal);
  EXPECT_GT(thermal[2], 60) << "thermal panel is not the cool end of the iron palette";
  EXPECT_GT(thermal[2], thermal[0]);
  EXPECT_GT(thermal[2], thermal[1]);
  EXPECT_LT(warm_fraction(img, kFigThermal), 0.001);
}

TEST(ViewSnapshot, SnapshotShowsAVictimAheadInEveryCamera) {
  const auto dir = temp_dir("snapshot-room");
  const auto scenario = write_victim_room(dir);
  const auto png = dir / "fig.png";
  const auto r = rescuesim("snapshot '" + scenario.string() + "' --time 1 --out '" + png.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Image img = decode(png);
  ASSERT_EQ(img.width, 1600);
  expect_content(img, {kFigMain, kFigLaser, kFigColour, kFigDepth, kFigThermal});
  // a person at 37 C, 2 m ahead, covers a few percent of the thermal image in warm colours
  EXPECT_GT(warm_fraction(img, kFigThermal), 0.005);
}

TEST(ViewSnapshot, WidthSetsTheFigureSize) {
  const auto dir = temp_dir("snapshot-width");
  const auto png = dir / "small.png";
  const auto r = rescuesim("snapshot --time 0.5 --width 800 --quality low --out '" + png.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // u = 0.5: m = 10, g = 6, text scale 1, panels 160 x 120, caption 28, title 10 + 14 + 6 = 30
  EXPECT_EQ(png_size(slurp(png)), std::make_pair(800, 30 + 2 * (120 + 28) + 12));
}

TEST(ViewSnapshot, BadQualityIsAUsageError) {
  const auto r = rescuesim("snapshot --quality ultra --out /dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("quality"), std::string::npos) << r.err;
  EXPECT_EQ(rescuesim("view --quality ultra").exit_code, 2);
}

TEST(ViewSnapshot, BadWidthIsAUsageError) {
  const auto r = rescuesim("snapshot --width 100 --out /dev/null");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("width"), std::string::npos) << r.err;
}

TEST(ViewSnapshot, SnapshotWithoutOpenGlSaysWhyAndExits2) {
  // libglvnd reads its EGL vendor list from this variable: a missing file leaves no EGL driver
  const auto r = run_command(std::string("env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json '") + RESCUESIM_EXE +
                             "' snapshot --time 0 --out /dev/null");
  if (r.exit_code == 0) GTEST_SKIP() << "this libEGL does not take __EGL_VENDOR_LIBRARY_FILENAMES (not libglvnd)";
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("Renderer::create_headless"), std::string::npos) << r.err;
}

TEST(ViewSnapshot, ViewWithoutDisplaySaysHowToGetOne) {
  const auto r = run_command(std::string("env -u DISPLAY -u WAYLAND_DISPLAY '") + RESCUESIM_EXE + "' view");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("rescuesim view needs a display"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xvfb-run -a rescuesim view"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rescuesim snapshot"), std::string::npos) << r.err;
}

TEST(ViewSnapshot, WindowScreenshotShowsMainViewAndFourPanels) {
  if (run_command("command -v xvfb-run").exit_code != 0) {
    std::printf("skipping: xvfb-run is not installed (Debian package xvfb)\n");
    GTEST_SKIP() << "xvfb-run is not installed";
  }
  const auto scenario = write_victim_room(temp_dir("view-room"));
  // kept under the build folder as a CI artefact
  const auto png = std::filesystem::path(RESCUESIM_BINARY_DIR) / "view-screenshot.png";
  std::filesystem::remove(png);
  const auto r = run_command(std::string("xvfb-run -a -s '-screen 0 1280x800x24' '") + RESCUESIM_EXE + "' view '" + scenario.string() +
                             "' --screenshot '" + png.string() + "' --after 2");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(png_size(slurp(png)), std::make_pair(1280, 800));
  const Image img = decode(png);
  ASSERT_EQ(img.width, 1280);
  ASSERT_EQ(img.height, 800);
  // window layout at 1280 x 800 (src/app/cmd_view.cpp): a 34 px toolbar; the main view left of
  // x = 742; right of it a 2 x 2 grid of 269 x 252 px panels whose 253 x 190 images start 8 px
  // in and 27 px down (under the title bar)
  const Region thermal{"thermal panel", 1019, 313, 253, 190};
  expect_content(img, {{"main view", 0, 34, 742, 766},
                       {"laser panel", 750, 61, 253, 190},
                       {"colour panel", 1019, 61, 253, 190},
                       {"depth panel", 750, 313, 253, 190},
                       thermal});
  EXPECT_GT(warm_fraction(img, thermal), 0.005) << "no warm victim in the thermal panel";
}

TEST(ViewSnapshot, TheScenariosControllerDrivesTheRobotInTheWindow) {
  // the default scenario's explorer drives off at up to 0.3 m/s; the simulation steps on its own
  // thread, with the built-in controller run after every step as in rescuesim run. By 8 s of
  // sim time it has driven more than a metre (a robot standing still drives 0 m).
  if (run_command("command -v xvfb-run").exit_code != 0) {
    std::printf("skipping: xvfb-run is not installed (Debian package xvfb)\n");
    GTEST_SKIP() << "xvfb-run is not installed";
  }
  const auto png = temp_dir("view-default") / "view.png";
  const auto r = run_command(std::string("xvfb-run -a -s '-screen 0 1280x800x24' '") + RESCUESIM_EXE + "' view --screenshot '" +
                             png.string() + "' --after 8");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  double t = 0, driven = -1;
  const auto at = r.out.find("rescuesim view: stopped at sim time");
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "rescuesim view: stopped at sim time %lf s; %lf m driven", &t, &driven), 2) << r.out;
  EXPECT_GE(t, 8.0);
  EXPECT_GT(driven, 1.0) << r.out;
}

}  // namespace
}  // namespace rescuesim
