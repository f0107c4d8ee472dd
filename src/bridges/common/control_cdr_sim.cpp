// The Simulation Interfaces' bodies (simulation_interfaces/msg and /srv; Result is in
// control_cdr_fields.h): their field lists and codecs. Where 1.x and 2.x differ, the field
// list asks the version.

#include "bridges/common/control_cdr_fields.h"

namespace rescuesim::control {

namespace wire {

// ---- simulation_interfaces/msg ----

template <>
struct Fields<SimulatorFeatures> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("features", m.features);
    io.sequence("spawn_formats", m.spawn_formats);
    io.string("custom_info", m.custom_info);
  }
};

template <>
struct Fields<TagsFilter> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("tags", m.tags);
    io.value("filter_mode", m.filter_mode);
  }
};

template <>
struct Fields<Bounds> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.value("type", m.type);
    messages(io, "points", m.points, v);
  }
};

template <>
struct Fields<EntityFilters> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("filter", m.filter);
    // EntityCategory[]: a sequence of one-byte messages {uint8 category}
    io.elements("categories", m.categories, 1, cdr::kUnbounded, [&](auto& c) { io.value("category", c); });
    message(io, "tags", m.tags, v);
    message(io, "bounds", m.bounds, v);
  }
};

template <>
struct Fields<EntityState> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.scope("header", [&] {
      io.stamp("stamp", m.stamp_ns);
      io.string("frame_id", m.frame_id);
    });
    message(io, "pose", m.pose, v);
    io.scope("twist", [&] {
      message(io, "linear", m.linear, v);
      message(io, "angular", m.angular, v);
    });
    io.scope("acceleration", [&] {
      message(io, "linear", m.linear_acc, v);
      message(io, "angular", m.angular_acc, v);
    });
  }
};

template <>
struct Fields<EntityInfo> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.scope("category", [&] { io.value("category", m.category); });
    io.string("description", m.description);
    io.sequence("tags", m.tags);
  }
};

template <>
struct Fields<NamedPose> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("name", m.name);
    io.string("description", m.description);
    io.sequence("tags", m.tags);
    message(io, "pose", m.pose, v);
  }
};

/// 1.x: string uri; 2.x: Resource entity_resource. Then description, spawn_bounds.
template <>
struct Fields<Spawnable> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    if (v == WireVersion::v1) {
      io.string("uri", m.uri);
    } else {
      resource(io, "entity_resource", m.uri, m.resource_string);
    }
    io.string("description", m.description);
    message(io, "spawn_bounds", m.spawn_bounds, v);
  }
};

template <>
struct Fields<WorldResource> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.string("name", m.name);
    resource(io, "world_resource", m.uri, m.resource_string);
    io.string("description", m.description);
    io.sequence("tags", m.tags);
  }
};

// ---- simulation_interfaces/srv bodies ----

template <>
struct Fields<Empty> {
  template <class IO, class M>
  static void visit(IO& io, M&, WireVersion) {
    std::uint8_t dummy = 0;  // rosidl's member of an empty struct
    io.value("structure_needs_at_least_one_member", dummy);
  }
};

template <>
struct Fields<ResetSimulationRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("scope", m.scope);
  }
};

template <>
struct Fields<SetSimulationStateRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.scope("state", [&] { enum8(io, "state", m.state); });
  }
};

template <>
struct Fields<GetSimulationStateResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.scope("state", [&] { enum8(io, "state", m.state); });
    message(io, "result", m.result, v);
  }
};

template <>
struct Fields<StepSimulationRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("steps", m.steps);
  }
};

template <>
struct Fields<EntityRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.string("entity", m.entity);
  }
};

template <>
struct Fields<SetEntityStateRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("entity", m.entity);
    message(io, "state", m.state, v);
    if (v == WireVersion::v2) {
      io.value("set_pose", m.set_pose);
      io.value("set_twist", m.set_twist);
      io.value("set_acceleration", m.set_acceleration);
    }
  }
};

template <>
struct Fields<NamedPoseBoundsRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.string("name", m.name);
  }
};

template <>
struct Fields<GetSpawnablesRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("sources", m.sources);
  }
};

/// name, allow_renaming, the resource (1.x: uri, resource_string; 2.x: the same in
/// entity_resource), entity_namespace, initial_pose (PoseStamped; its stamp is dropped).
template <>
struct Fields<SpawnRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("name", m.name);
    io.value("allow_renaming", m.allow_renaming);
    if (v == WireVersion::v1) {
      io.string("uri", m.uri);
      io.string("resource_string", m.resource_string);
    } else {
      resource(io, "entity_resource", m.uri, m.resource_string);
    }
    io.string("entity_namespace", m.entity_namespace);
    io.scope("initial_pose", [&] {
      io.scope("header", [&] {
        std::int64_t stamp_ns = 0;
        io.stamp("stamp", stamp_ns);
        io.string("frame_id", m.frame_id);
      });
      message(io, "pose", m.pose, v);
    });
  }
};

template <>
struct Fields<GetAvailableWorldsRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.sequence("additional_sources", m.additional_sources);
    message(io, "filter", m.filter, v);
    io.value("offline_only", m.offline_only);
    io.value("continue_on_error", m.continue_on_error);
  }
};

template <>
struct Fields<LoadWorldRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    if (v == WireVersion::v1) {
      io.string("uri", m.uri);
      io.string("resource_string", m.resource_string);
    } else {
      resource(io, "world_resource", m.uri, m.resource_string);
    }
    io.value("fail_on_unsupported_element", m.fail_on_unsupported_element);
    io.value("ignore_missing_or_unsupported_assets", m.ignore_missing_or_unsupported_assets);
  }
};

template <>
struct Fields<GetEntitiesResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    io.sequence("entities", m.entities);
  }
};

template <>
struct Fields<GetEntityStateResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    message(io, "state", m.state, v);
  }
};

template <>
struct Fields<GetEntitiesStatesResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    io.sequence("entities", m.entities);
    messages(io, "states", m.states, v);
  }
};

template <>
struct Fields<GetEntityInfoResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    message(io, "info", m.info, v);
  }
};

template <>
struct Fields<BoundsResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    message(io, "bounds", m.bounds, v);
  }
};

template <>
struct Fields<GetNamedPosesResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    messages(io, "poses", m.poses, v);
  }
};

template <>
struct Fields<GetSpawnablesResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    messages(io, "spawnables", m.spawnables, v);
  }
};

template <>
struct Fields<SpawnEntityResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    io.string("entity_name", m.entity_name);
  }
};

template <>
struct Fields<GetAvailableWorldsResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    messages(io, "worlds", m.worlds, v);
  }
};

template <>
struct Fields<WorldResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    message(io, "result", m.result, v);
    message(io, "world", m.world, v);
  }
};

}  // namespace wire

RS_CONTROL_CDR_SERVICE(GetSimulatorFeatures)
RS_CONTROL_CDR_SERVICE(ResetSimulation)
RS_CONTROL_CDR_SERVICE(GetSimulationState)
RS_CONTROL_CDR_SERVICE(SetSimulationState)
RS_CONTROL_CDR_SERVICE(StepSimulation)
RS_CONTROL_CDR_SERVICE(GetEntities)
RS_CONTROL_CDR_SERVICE(GetEntityState)
RS_CONTROL_CDR_SERVICE(GetEntitiesStates)
RS_CONTROL_CDR_SERVICE(SetEntityState)
RS_CONTROL_CDR_SERVICE(GetEntityInfo)
RS_CONTROL_CDR_SERVICE(GetEntityBounds)
RS_CONTROL_CDR_SERVICE(GetNamedPoses)
RS_CONTROL_CDR_SERVICE(GetNamedPoseBounds)
RS_CONTROL_CDR_SERVICE(GetSpawnables)
RS_CONTROL_CDR_SERVICE(SpawnEntity)
RS_CONTROL_CDR_SERVICE(DeleteEntity)
RS_CONTROL_CDR_SERVICE(GetAvailableWorlds)
RS_CONTROL_CDR_SERVICE(GetCurrentWorld)
RS_CONTROL_CDR_SERVICE(LoadWorld)
RS_CONTROL_CDR_SERVICE(UnloadWorld)

}  // namespace rescuesim::control
