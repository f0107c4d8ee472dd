// A Foxglove WebSocket client (@foxglove/ws-protocol) watching `rescuesim replay --foxglove`:
// subscribes to /scan and /clock, decodes the scans, follows the server's time, sends one
// /cmd_vel (which a replay must ignore), and prints what it saw as JSON after SECONDS.
//   node replay_foxglove.js ws://127.0.0.1:PORT SECONDS
"use strict";
const WebSocket = require("ws");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [url, seconds] = process.argv.slice(2);
const out = { connected: false, scans: 0, clocks: 0, lastClock: 0, maxTime: 0, scan: null, sentCmdVel: false, error: "" };
const channels = new Map();  // subscription id -> {topic, reader}

function connect() {
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  client.on("error", () => {});
  client.on("close", () => {
    if (!out.connected) setTimeout(connect, 100);  // the server is not up yet
  });
  client.on("open", () => (out.connected = true));
  client.on("serverInfo", (info) => {
    if ((info.capabilities ?? []).includes("clientPublish")) {
      const id = client.advertise({ topic: "/cmd_vel", encoding: "json", schemaName: "geometry_msgs/msg/Twist" });
      setTimeout(() => {
        client.sendMessage(id, new TextEncoder().encode(JSON.stringify({ linear: { x: 0.3 }, angular: { z: 0.2 } })));
        out.sentCmdVel = true;
      }, 300);
    }
  });
  client.on("advertise", (list) => {
    for (const ch of list) {
      if (ch.topic !== "/scan" && ch.topic !== "/clock") continue;
      const reader = new MessageReader(parse(ch.schema, { ros2: true }));
      channels.set(client.subscribe(ch.id), { topic: ch.topic, reader });
    }
  });
  client.on("time", ({ timestamp }) => (out.maxTime = Math.max(out.maxTime, Number(timestamp))));
  client.on("message", ({ subscriptionId, data }) => {
    const ch = channels.get(subscriptionId);
    if (!ch) return;
    try {
      const m = ch.reader.readMessage(data);
      if (ch.topic === "/scan") {
        out.scans += 1;
        out.scan = { ranges: m.ranges.length, frameId: m.header.frame_id, stamp: m.header.stamp.sec * 1e9 + m.header.stamp.nanosec };
      } else {
        out.clocks += 1;
        out.lastClock = m.clock.sec * 1e9 + m.clock.nanosec;
      }
    } catch (e) {
      out.error = String(e.message ?? e);
    }
  });
}

connect();
setTimeout(() => {
  process.stdout.write(JSON.stringify(out) + "\n");
  process.exit(0);
}, Number(seconds) * 1000);
