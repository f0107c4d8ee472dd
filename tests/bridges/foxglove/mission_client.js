// A mission's inputs from a Foxglove client, as a publish panel or a team's own client would
// send them: @foxglove/ws-protocol's FoxgloveClient advertises robot A's rescue/report in json
// (geometry_msgs/msg/PoseStamped) and its rescue/comms/send in cdr (std_msgs/msg/String, written
// with the schema the server advertised for a String channel), reports a victim at X Y Z, sends
// robot B a datagram, and reads the referee's answer on A's report_result and the datagram on
// B's comms/inbox. On the way it sends a malformed report and collects the status reply.
// Prints one JSON object.
// Usage: node mission_client.js ws://127.0.0.1:PORT /A_NS B_NAME X Y Z
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");

const [url, a, b, x, y, z] = process.argv.slice(2);
const out = { statuses: [], answers: [], inbox: [], errors: [] };
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

// subscription id -> { reader, into }
const readers = new Map();
let stringWriter = null;
client.on("advertise", (channels) => {
  for (const [topic, into] of [
    [a + "/rescue/report_result", out.answers],
    ["/" + b + "/rescue/comms/inbox", out.inbox],
  ]) {
    const c = channels.find((ch) => ch.topic === topic);
    if (!c) continue;
    const definition = parse(c.schema, { ros2: true });
    readers.set(client.subscribe(c.id), { reader: new MessageReader(definition), into });
    if (!stringWriter) stringWriter = new MessageWriter(definition);
  }
});
client.on("message", ({ subscriptionId, data }) => {
  const r = readers.get(subscriptionId);
  if (r) r.into.push(JSON.parse(r.reader.readMessage(data).data));
});

client.on("open", async () => {
  try {
    if (!(await until(() => readers.size === 2, 15000))) throw new Error("the server did not advertise the mission's answer topics");
    phase = "advertise";
    const report = client.advertise({ topic: a + "/rescue/report", encoding: "json", schemaName: "geometry_msgs/msg/PoseStamped" });
    const send = client.advertise({ topic: a + "/rescue/comms/send", encoding: "cdr", schemaName: "std_msgs/msg/String" });
    await sleep(300);

    phase = "malformed";
    const before = out.statuses.length;
    client.sendMessage(report, json({ header: { frame_id: "map" }, pose: { position: { x: "far" } } }));
    await until(() => out.statuses.length > before, 3000);

    phase = "report";
    client.sendMessage(report, json({ header: { frame_id: "map" }, pose: { position: { x: Number(x), y: Number(y), z: Number(z) } } }));
    phase = "send";
    client.sendMessage(send, stringWriter.writeMessage({ data: JSON.stringify({ to: b, text: "victim near " + x + "," + y }) }));
    phase = "answers";
    await until(() => out.answers.length > 0 && out.inbox.length > 0, 15000);
    phase = "done";
    client.close();
    finish(out.errors.length ? 1 : 0);
  } catch (e) {
    out.errors.push(e.message);
    finish(1);
  }
});
