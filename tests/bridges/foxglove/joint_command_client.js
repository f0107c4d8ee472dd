// Commands a robot's joints the way a Foxglove panel publishing sensor_msgs/JointState would:
// @foxglove/ws-protocol's FoxgloveClient advertises joint_command channels in json and cdr,
// publishes a target for the prismatic joint "lift" in each, and watches the robot's
// joint_states (cdr, decoded with the schema the server advertised) until the joint is there.
// On the way it advertises joint_command for a robot without commandable joints and sends a
// wheel command and a malformed one, collecting the status replies. It also reads the robot's
// robot_description, the latched text the 3D panel's URDF layer shows. Prints one JSON object.
// Usage: node joint_command_client.js ws://127.0.0.1:PORT /SLIDER_NS /OTHER_NS
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");

const [url, slider, other] = process.argv.slice(2);
const out = { statuses: [], phases: {}, description: null, errors: [] };
let phase = "connect";

function finish(code) {
  process.stdout.write(JSON.stringify(out) + "\n");
  process.exit(code);
}
setTimeout(() => {
  out.errors.push("timed out in phase " + phase);
  finish(1);
}, 40000);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
/// Resolves true once `pred()` holds, false after `ms`.
async function until(pred, ms) {
  const deadline = Date.now() + ms;
  while (Date.now() < deadline) {
    if (pred()) return true;
    await sleep(10);
  }
  return pred();
}
const json = (value) => new TextEncoder().encode(JSON.stringify(value));

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => out.errors.push(String(e && e.message ? e.message : e)));
client.on("status", (s) => out.statuses.push({ phase, level: s.level, message: s.message }));

let states = null; // { subscription, reader, writer }
let lift = null; // last position of "lift" on joint_states (m)
let description = null; // { subscription, reader }
client.on("advertise", (channels) => {
  const d = channels.find((x) => x.topic === slider + "/robot_description");
  if (d && !description) {
    out.description = { schemaName: d.schemaName, encoding: d.encoding, data: null };
    description = { reader: new MessageReader(parse(d.schema, { ros2: true })), subscription: client.subscribe(d.id) };
  }
  const c = channels.find((x) => x.topic === slider + "/joint_states");
  if (!c || states) return;
  // the server's own ros2msg schema for sensor_msgs/msg/JointState reads its messages and
  // writes ours, as Foxglove's publish panels do with the datatypes they know
  const definition = parse(c.schema, { ros2: true });
  states = { reader: new MessageReader(definition), writer: new MessageWriter(definition), subscription: client.subscribe(c.id) };
});
client.on("message", ({ subscriptionId, data }) => {
  if (description && subscriptionId === description.subscription) {
    out.description.data = description.reader.readMessage(data).data;
    return;
  }
  if (!states || subscriptionId !== states.subscription) return;
  const m = states.reader.readMessage(data);
  const i = m.name.indexOf("lift");
  if (i >= 0) lift = m.position[i];
});

/// Sends `payload` on `channel` and waits up to 3 s for the next status reply.
async function expectStatus(label, channel, payload) {
  phase = label;
  const before = out.statuses.length;
  client.sendMessage(channel, payload);
  await until(() => out.statuses.length > before, 3000);
}

/// Sends one lift target on `channel`; records when joint_states shows it within 1 mm.
async function drive(label, channel, payload, target) {
  phase = label;
  const start = Date.now();
  client.sendMessage(channel, payload);
  const reached = await until(() => lift !== null && Math.abs(lift - target) < 1e-3, 15000);
  out.phases[label] = { reached, lift, ms: Date.now() - start };
}

client.on("open", async () => {
  try {
    if (!(await until(() => lift !== null, 15000))) throw new Error("no " + slider + "/joint_states");

    // a robot whose joints are all wheels and head: an error naming what it takes; the slider's
    // joint_command in json (ROS 2 schema name) and cdr (ROS 1 schema name): accepted silently
    phase = "advertise";
    client.advertise({ topic: other + "/joint_command", encoding: "json", schemaName: "sensor_msgs/msg/JointState" });
    const inJson = client.advertise({ topic: slider + "/joint_command", encoding: "json", schemaName: "sensor_msgs/msg/JointState" });
    const inCdr = client.advertise({ topic: slider + "/joint_command", encoding: "cdr", schemaName: "sensor_msgs/JointState" });
    await sleep(500);
    // a topic nobody takes: the error lists what every robot takes
    phase = "foreign";
    const before = out.statuses.length;
    client.advertise({ topic: "/not_ours", encoding: "json", schemaName: "std_msgs/msg/String" });
    await until(() => out.statuses.length > before, 3000);

    await drive("json", inJson, json({ name: ["lift"], position: [0.15] }), 0.15);
    await expectStatus("wheel", inJson, json({ name: ["wheel"], velocity: [1.0] }));
    await expectStatus("malformed", inJson, json({ name: ["lift"], position: ["high"] }));
    const cdr = states.writer.writeMessage({
      header: { stamp: { sec: 0, nanosec: 0 }, frame_id: "" },
      name: ["lift"],
      position: [-0.05],
      velocity: [],
      effort: [],
    });
    await drive("cdr", inCdr, cdr, -0.05);
    await until(() => out.description && out.description.data !== null, 5000);
    phase = "done";
    client.close();
    finish(out.errors.length ? 1 : 0);
  } catch (e) {
    out.errors.push(e.message);
    finish(1);
  }
});
