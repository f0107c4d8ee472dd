// A client driving a robot spawned while it is connected, by name, as robots before it are
// deleted: once /b/scan is advertised it advertises /b/cmd_vel (json) and sends linear.x 0.25;
// when /a's channels are unadvertised (a deleted, b one index down) it sends 0.5 on the same
// channel; when /b's are (b deleted) it sends 0.75 and waits for the status error that refuses
// it, then prints one JSON object.
// Usage: node spawn_command_client.js ws://127.0.0.1:PORT
"use strict";
const { startClient } = require("./client_support");

const [url] = process.argv.slice(2);
const out = { sent: [], refusals: [], errors: [] };
const { client, finish } = startClient(url, out, 60000);
const channelOf = {};  // topic -> server channel id
let cmd = null;
const send = (x) => {
  out.sent.push(x);
  const twist = { linear: { x, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } };
  client.sendMessage(cmd, new TextEncoder().encode(JSON.stringify(twist)));
};
let connected = false;
client.on("advertise", (channels) => {
  for (const c of channels) channelOf[c.topic] = c.id;
  if (!connected) {
    // /clock, so the server sees a subscriber (the test steps until something was sent)
    connected = true;
    if (channelOf["/clock"] !== undefined) client.subscribe(channelOf["/clock"]);
  }
  if (!cmd && channels.some((c) => c.topic === "/b/scan")) {
    cmd = client.advertise({ topic: "/b/cmd_vel", encoding: "json", schemaName: "geometry_msgs/msg/Twist" });
    send(0.25);
  }
});
client.on("unadvertise", (ids) => {
  if (!cmd) return;
  if (ids.includes(channelOf["/a/scan"])) send(0.5);
  if (ids.includes(channelOf["/b/scan"])) send(0.75);
});
client.on("status", (s) => {
  if (out.sent.length < 3) {
    out.errors.push("status: " + s.message);
    return;
  }
  out.refusals.push({ level: s.level, message: s.message });
  if (s.level === 2) {
    client.close();
    finish(0);
  }
});
