// The SimulateSteps action's bodies (the types rosidl derives from SimulateSteps.action) and
// action_msgs's CancelGoal and GoalStatusArray: their field lists and codecs.

#include "bridges/common/control_cdr_fields.h"

namespace rescuesim::control {

namespace wire {

// ---- the SimulateSteps action, action_msgs ----

/// unique_identifier_msgs/msg/UUID under `name`.
template <class IO, class G>
void goal_id(IO& io, const char* name, G& id) {
  io.scope(name, [&] { io.octets("uuid", id); });
}

template <>
struct Fields<SendGoalRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    goal_id(io, "goal_id", m.goal_id);
    io.scope("goal", [&] { io.value("steps", m.steps); });
  }
};

template <>
struct Fields<SendGoalResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("accepted", m.accepted);
    io.stamp("stamp", m.stamp_ns);
  }
};

template <>
struct Fields<GetResultRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    goal_id(io, "goal_id", m.goal_id);
  }
};

/// status, then SimulateSteps_Result result {Result result}.
template <>
struct Fields<GetResultResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.value("status", m.status);
    io.scope("result", [&] { message(io, "result", m.result, v); });
  }
};

template <>
struct Fields<FeedbackMessage> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    goal_id(io, "goal_id", m.goal_id);
    io.scope("feedback", [&] {
      io.value("completed_steps", m.completed_steps);
      io.value("remaining_steps", m.remaining_steps);
    });
  }
};

template <>
struct Fields<GoalInfo> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    goal_id(io, "goal_id", m.goal_id);
    io.stamp("stamp", m.stamp_ns);
  }
};

template <>
struct Fields<CancelGoalRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "goal_info", m.goal_info, v);
  }
};

template <>
struct Fields<CancelGoalResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.value("return_code", m.return_code);
    messages(io, "goals_canceling", m.goals_canceling, v);
  }
};

template <>
struct Fields<GoalStatus> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "goal_info", m.goal_info, v);
    io.value("status", m.status);
  }
};

template <>
struct Fields<GoalStatusArray> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    messages(io, "status_list", m.status_list, v);
  }
};

}  // namespace wire

RS_CONTROL_CDR_SERVICE(SimulateStepsSendGoal)
RS_CONTROL_CDR_SERVICE(SimulateStepsGetResult)
RS_CONTROL_CDR_SERVICE(CancelGoal)
RS_CONTROL_CDR_TOPIC(SimulateStepsFeedback)
RS_CONTROL_CDR_TOPIC(SimulateStepsStatus)

}  // namespace rescuesim::control
