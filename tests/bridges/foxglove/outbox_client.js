// Subscribes to /burst (geometry_msgs/PoseStamped, pose.position.x numbers them), /big and
// /big2 (sensor_msgs/Image, every byte of data set to the image's marker) and last to /probe
// (so once the server sends /probe, the other subscriptions are in), and records what arrives
// until it has the /burst message numbered LAST_X and the /big image marked LAST_MARKER; then
// prints one JSON object.
// Usage: node outbox_client.js ws://127.0.0.1:PORT LAST_X LAST_MARKER
"use strict";
const { startClient } = require("./client_support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [url, lastXArg, lastMarkerArg] = process.argv.slice(2);
const lastX = Number(lastXArg);
const lastMarker = Number(lastMarkerArg);
const out = { bursts: [], images: [], probes: 0, errors: [] };
const { client, finish } = startClient(url, out, 60000);
const subs = new Map();  // subscription id -> { topic, reader }
let subscribed = false;
client.on("advertise", (channels) => {
  if (subscribed) return;
  const find = (topic) => channels.find((c) => c.topic === topic);
  const wanted = ["/burst", "/big", "/big2", "/probe"].map(find).filter((c) => c);
  if (!find("/burst") || !find("/big") || !find("/probe")) return;
  subscribed = true;
  for (const c of wanted) subs.set(client.subscribe(c.id), { topic: c.topic, reader: new MessageReader(parse(c.schema, { ros2: true })) });
});
let gotX = false;
let gotMarker = false;
client.on("message", ({ subscriptionId, data }) => {
  const s = subs.get(subscriptionId);
  if (!s) return;
  const m = s.reader.readMessage(data);
  if (s.topic === "/probe") {
    ++out.probes;
  } else if (s.topic === "/burst") {
    out.bursts.push(m.pose.position.x);
    if (m.pose.position.x === lastX) gotX = true;
  } else {
    const marker = m.data.length > 0 ? m.data[0] : -1;
    out.images.push({ topic: s.topic, marker, bytes: m.data.length, uniform: m.data.every((b) => b === marker) });
    if (s.topic === "/big" && marker === lastMarker) gotMarker = true;
  }
  if (gotX && gotMarker) {
    client.close();
    finish(0);
  }
});
