// The mission calls of an environment's robot (EnvCore): victim reports, datagrams, relays,
// link status and the score, as plain Python values. See docs/missions.md.

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "core/error.h"
#include "env_core.h"
#include "session/session.h"

namespace py = pybind11;

namespace rescuesim::python {

namespace {

/// The environment's mission; Error (RuntimeError in Python) without one.
Mission& mission_of(EnvCore& e) {
  if (!e.session()) throw Error("call reset() first");
  Mission* m = e.session()->mission();
  if (!m) throw Error("the scenario has no mission: block (docs/missions.md)");
  return *m;
}

py::object or_none(bool present, py::object value) { return present ? std::move(value) : py::none(); }

/// A report's picture from numpy: uint8, H x W (mono8), H x W x 3 (rgb8) or H x W x 4 (rgba8).
msg::Image picture_of(const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
  const auto nd = a.ndim();
  const std::size_t channels = nd == 2 ? 1 : nd == 3 ? static_cast<std::size_t>(a.shape(2)) : 0;
  if (channels != 1 && channels != 3 && channels != 4) {
    throw Error("a report's image is a uint8 array of H x W (grey), H x W x 3 (RGB) or H x W x 4 (RGBA)");
  }
  msg::Image im;
  im.height = static_cast<std::uint32_t>(a.shape(0));
  im.width = static_cast<std::uint32_t>(a.shape(1));
  im.encoding = channels == 1 ? "mono8" : channels == 3 ? "rgb8" : "rgba8";
  im.step = static_cast<std::uint32_t>(im.width * channels);
  im.data.assign(a.data(), a.data() + a.size());
  return im;
}

}  // namespace

void add_mission_methods(py::class_<EnvCore>& cls) {
  cls.def(
         "report",
         [](EnvCore& e, double x, double y, double z, const py::object& image) {
           Mission& m = mission_of(e);
           const ReportReply r =
               image.is_none() ? m.report(e.robot_index(), {x, y, z})
                               : m.report(e.robot_index(), {x, y, z},
                                          picture_of(image.cast<py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>>()));
           py::dict d;
           d["id"] = r.id;
           d["outcome"] = std::string(report_outcome_name(r.outcome));
           d["victim"] = or_none(r.victim.valid(), r.victim.valid() ? py::str(m.referee().victims()[r.victim.slot()].name) : py::str());
           d["distance"] = or_none(r.distance_m >= 0, py::float_(r.distance_m));
           d["score_change"] = r.score_change;
           d["score"] = r.score;
           d["reports_left"] = r.reports_left;
           d["message"] = r.message;
           return d;
         },
         py::arg("x"), py::arg("y"), py::arg("z") = 0.0, py::arg("image") = py::none(),
         "reports a victim at (x, y, z) in the map frame, with an optional picture (uint8 numpy array); -> the referee's answer")
      .def(
          "send",
          [](EnvCore& e, const std::string& to, const py::bytes& data) {
            const std::string bytes = data;
            const SendResult r = mission_of(e).send(e.robot_index(), to, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
            return py::make_tuple(r.accepted, r.reason);
          },
          py::arg("to"), py::arg("data"), "queues a datagram to a robot, a base or '*' (every neighbour); -> (accepted, reason)")
      .def(
          "inbox",
          [](EnvCore& e) {
            Mission& m = mission_of(e);
            py::list out;
            for (const Datagram& d : m.take_inbox(e.robot_index())) {
              py::dict x;
              x["from"] = m.network().node(d.from).id;
              x["data"] = py::bytes(reinterpret_cast<const char*>(d.bytes.data()), d.bytes.size());
              x["hops"] = d.hops();
              x["sent"] = d.sent.seconds();
              x["delivered"] = d.delivered.seconds();
              out.append(x);
            }
            return out;
          },
          "takes the datagrams delivered to this robot, oldest first")
      .def(
          "comms_status",
          [](EnvCore& e) {
            Mission& m = mission_of(e);
            const RadioStatus st = m.status(e.robot_index());
            py::dict d;
            d["in_contact"] = m.in_contact(e.robot_index());
            d["hops_to_base"] = or_none(st.hops_to_base.has_value(), py::int_(st.hops_to_base.value_or(-1)));
            py::list nb;
            for (const auto& n : st.neighbours) nb.append(py::make_tuple(m.network().node(n.node).id, n.rssi_dbm, n.margin_db));
            d["neighbours"] = nb;
            d["bytes_sent"] = st.bytes_sent;
            d["bytes_received"] = st.bytes_received;
            d["bytes_dropped"] = st.bytes_dropped;
            d["relays_left"] = m.network().relays_left(m.robot_node(e.robot_index()));
            return d;
          },
          "link status at the last link update: in_contact, hops_to_base, neighbours [(id, rssi_dbm, margin_db)], bytes, relays_left")
      .def(
          "drop_relay",
          [](EnvCore& e) {
            Mission& m = mission_of(e);
            const RelayResult r = m.drop_relay(e.robot_index());
            return py::make_tuple(r.ok(), r.ok() ? m.network().node(r.node).id : r.reason);
          },
          "drops a relay where the robot stands; -> (ok, relay id or the reason it could not)")
      .def(
          "mission_score",
          [](EnvCore& e) -> py::object {
            if (!e.session() || !e.session()->mission()) return py::none();
            const Referee& r = e.session()->mission()->referee();
            py::dict d;
            d["score"] = r.score();
            d["victims_found"] = r.victims_found();
            d["victims"] = r.victim_count();
            d["false_reports"] = r.counts()[ReportOutcome::false_report];
            d["reports"] = r.counts().charged;
            d["reports_left"] = r.reports_left();
            return d;
          },
          "the referee's score so far, or None without a mission");
}

}  // namespace rescuesim::python
