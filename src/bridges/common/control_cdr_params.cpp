// The rcl_interfaces parameter services' bodies: their field lists and codecs.

#include "bridges/common/control_cdr_fields.h"

namespace rescuesim::control {

namespace wire {

// ---- rcl_interfaces ----

template <>
struct Fields<ParameterValue> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("type", m.type);
    io.value("bool_value", m.bool_value);
    io.value("integer_value", m.integer_value);
    io.value("double_value", m.double_value);
    io.string("string_value", m.string_value);
    io.sequence("byte_array_value", m.byte_array_value);
    io.sequence("bool_array_value", m.bool_array_value);
    io.sequence("integer_array_value", m.integer_array_value);
    io.sequence("double_array_value", m.double_array_value);
    io.sequence("string_array_value", m.string_array_value);
  }
};

template <>
struct Fields<Parameter> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("name", m.name);
    message(io, "value", m.value, v);
  }
};

template <>
struct Fields<SetParameterResult> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("successful", m.successful);
    io.string("reason", m.reason);
  }
};

template <>
struct Fields<FloatingPointRange> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("from_value", m.from_value);
    io.value("to_value", m.to_value);
    io.value("step", m.step);
  }
};

template <>
struct Fields<IntegerRange> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.value("from_value", m.from_value);
    io.value("to_value", m.to_value);
    io.value("step", m.step);
  }
};

template <>
struct Fields<ParameterDescriptorMessage> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    io.string("name", m.name);
    io.value("type", m.type);
    io.string("description", m.description);
    io.string("additional_constraints", m.additional_constraints);
    io.value("read_only", m.read_only);
    io.value("dynamic_typing", m.dynamic_typing);
    messages(io, "floating_point_range", m.floating_point_range, v, 1);
    messages(io, "integer_range", m.integer_range, v, 1);
  }
};

template <>
struct Fields<ListParametersRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("prefixes", m.prefixes);
    io.value("depth", m.depth);
  }
};

template <>
struct Fields<ListParametersResult> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("names", m.names);
    io.sequence("prefixes", m.prefixes);
  }
};

template <>
struct Fields<ParameterNames> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("names", m.names);
  }
};

template <>
struct Fields<GetParametersResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    messages(io, "values", m.values, v);
  }
};

template <>
struct Fields<SetParametersRequest> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    messages(io, "parameters", m.parameters, v);
  }
};

template <>
struct Fields<SetParametersResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    messages(io, "results", m.results, v);
  }
};

template <>
struct Fields<DescribeParametersResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion v) {
    messages(io, "descriptors", m.descriptors, v);
  }
};

template <>
struct Fields<GetParameterTypesResponse> {
  template <class IO, class M>
  static void visit(IO& io, M& m, WireVersion) {
    io.sequence("types", m.types);
  }
};

}  // namespace wire

RS_CONTROL_CDR_SERVICE(ListParameters)
RS_CONTROL_CDR_SERVICE(GetParameters)
RS_CONTROL_CDR_SERVICE(SetParameters)
RS_CONTROL_CDR_SERVICE(SetParametersAtomically)
RS_CONTROL_CDR_SERVICE(DescribeParameters)
RS_CONTROL_CDR_SERVICE(GetParameterTypes)

}  // namespace rescuesim::control
