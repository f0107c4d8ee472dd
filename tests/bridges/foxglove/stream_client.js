// A Foxglove client as Foxglove itself is built: @foxglove/ws-protocol's FoxgloveClient over
// `ws`, CDR decoded with @foxglove/rosmsg + @foxglove/rosmsg2-serialization. It subscribes to
// the laser, the colour camera, odometry and the scene, then drives the robot by publishing
// /cmd_vel (cdr) like Foxglove's teleop panel, and prints what it saw as one JSON object.
// Usage: node stream_client.js ws://127.0.0.1:PORT [drive_seconds] [speed]
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");

const url = process.argv[2];
const driveSeconds = Number(process.argv[3] ?? 2);
const speed = Number(process.argv[4] ?? 0.3);

const out = {
  serverInfo: null,
  channels: [],
  statuses: [],
  times: { count: 0, first: null, last: null, monotonic: true },
  scan: null,
  image: null,
  scene: null,
  odom: [],
  counts: {},
  errors: [],
  drive: null,
};

function finish(code) {
  process.stdout.write(JSON.stringify(out) + "\n");
  process.exit(code);
}
setTimeout(() => {
  out.errors.push("timed out");
  finish(1);
}, 30000);

const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const channels = new Map(); // id -> channel
const readers = new Map(); // channel id -> MessageReader
const subs = new Map(); // subscription id -> channel
const toNs = (t) => Number(t);

client.on("error", (e) => out.errors.push(String(e && e.message ? e.message : e)));
client.on("serverInfo", (info) => (out.serverInfo = info));
client.on("status", (s) => out.statuses.push(s));
client.on("time", ({ timestamp }) => {
  const t = toNs(timestamp);
  if (out.times.last !== null && t < out.times.last) out.times.monotonic = false;
  if (out.times.first === null) out.times.first = t;
  out.times.last = t;
  out.times.count++;
});

let started = false;
client.on("advertise", (list) => {
  for (const c of list) {
    channels.set(c.id, c);
    out.channels.push({ id: c.id, topic: c.topic, encoding: c.encoding, schemaName: c.schemaName, schemaEncoding: c.schemaEncoding });
    if (c.encoding === "cdr") readers.set(c.id, new MessageReader(parse(c.schema, { ros2: true })));
  }
  if (started) return;
  started = true;
  for (const topic of ["/scan", "/camera/color/image_raw", "/odom", "/scene"]) {
    const c = [...channels.values()].find((x) => x.topic === topic);
    if (!c) {
      out.errors.push("no channel " + topic);
      continue;
    }
    subs.set(client.subscribe(c.id), c);
  }
});

client.on("message", ({ subscriptionId, timestamp, data }) => {
  const c = subs.get(subscriptionId);
  if (!c) return out.errors.push("message for unknown subscription " + subscriptionId);
  out.counts[c.topic] = (out.counts[c.topic] ?? 0) + 1;
  const receive = toNs(timestamp);
  try {
    if (c.encoding === "json") {
      const m = JSON.parse(new TextDecoder().decode(data));
      if (!out.scene) {
        out.scene = { receive, entities: m.entities.map((e) => ({ id: e.id, frame_id: e.frame_id, frame_locked: e.frame_locked,
          cubes: e.cubes, spheres: e.spheres.length, cylinders: e.cylinders.length, triangles: e.triangles.length, texts: e.texts })) };
      }
      return;
    }
    const m = readers.get(c.id).readMessage(data);
    const stamp = m.header ? m.header.stamp.sec * 1e9 + m.header.stamp.nanosec : null;
    if (c.topic === "/scan" && !out.scan) {
      const n = m.ranges.length;
      out.scan = { receive, stamp, frame_id: m.header.frame_id, angle_min: m.angle_min, angle_max: m.angle_max,
        angle_increment: m.angle_increment, range_min: m.range_min, range_max: m.range_max, count: n,
        ahead: m.ranges[(n - 1) / 2], trailing: readers.get(c.id).lastReadHadTrailingBytes() };
    } else if (c.topic === "/camera/color/image_raw" && !out.image) {
      out.image = { receive, stamp, frame_id: m.header.frame_id, width: m.width, height: m.height, encoding: m.encoding,
        step: m.step, is_bigendian: m.is_bigendian, bytes: m.data.length };
    } else if (c.topic === "/odom") {
      out.odom.push({ receive, stamp, x: m.pose.pose.position.x, y: m.pose.pose.position.y, v: m.twist.twist.linear.x,
        frame_id: m.header.frame_id, child: m.child_frame_id });
    }
  } catch (e) {
    out.errors.push(c.topic + ": " + e.message);
  }
});

client.on("open", () => {
  // once the first scan, image and scene are in, drive: cmd_vel at 20 Hz like a teleop panel
  const waitForData = setInterval(() => {
    if (!out.scan || !out.image || !out.scene || out.odom.length === 0) return;
    clearInterval(waitForData);
    const twistDef = parse("geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n" +
      "================================================================================\nMSG: geometry_msgs/Vector3\n" +
      "float64 x\nfloat64 y\nfloat64 z\n", { ros2: true });
    const writer = new MessageWriter(twistDef);
    const cmd = client.advertise({ topic: "/cmd_vel", encoding: "cdr", schemaName: "geometry_msgs/msg/Twist" });
    const bytes = writer.writeMessage({ linear: { x: speed, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } });
    out.drive = { start_odom_count: out.odom.length, start_time: out.times.last };
    const send = setInterval(() => client.sendMessage(cmd, bytes), 50);
    setTimeout(() => {
      clearInterval(send);
      out.drive.end_time = out.times.last;
      out.drive.end_odom_count = out.odom.length;
      // let the robot stop (command timeout) and the last odometry arrive
      setTimeout(() => {
        client.close();
        finish(out.errors.length ? 1 : 0);
      }, 800);
    }, driveSeconds * 1000);
  }, 20);
});
client.on("close", () => {
  if (!out.drive || out.drive.end_time === undefined) {
    out.errors.push("connection closed early");
    finish(1);
  }
});
