// A client watching a robot spawned and deleted while it is connected: subscribes to /clock at
// connect (so the server sees a subscriber), and to NS's scan and robot_description once they
// are advertised; counts the scans and keeps their stamps; records the channels unadvertised;
// once the scan channel is unadvertised, waits for it to be advertised again (the topics
// advertised then: readvertised), then prints one
// JSON object. STATUS (a file) says how far it got, for the test stepping the simulation:
// {"ready": subscribed to the scan and the description arrived, "scans": N, "unadvertised": bool}.
// Usage: node spawn_channels_client.js ws://127.0.0.1:PORT STATUS NS
"use strict";
const fs = require("fs");
const { startClient } = require("./client_support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [url, statusFile, ns] = process.argv.slice(2);
const scanTopic = `/${ns}/scan`;
const descriptionTopic = `/${ns}/robot_description`;
const out = {
  channelsAtConnect: null, advertised: [], unadvertised: [], description: null, scanStamps: [], scansAfterUnadvertise: 0,
  readvertised: null, errors: [],
};
const status = { ready: false, scans: 0, unadvertised: false };
const writeStatus = () => {
  fs.writeFileSync(statusFile + ".tmp", JSON.stringify(status));
  fs.renameSync(statusFile + ".tmp", statusFile);
};
const { client, finish } = startClient(url, out, 60000);
client.on("status", (s) => out.errors.push("status: " + s.message));
let scan = null, description = null;  // { id, subscription, reader }
const subscribeTo = (c) => ({ id: c.id, reader: new MessageReader(parse(c.schema, { ros2: true })), subscription: client.subscribe(c.id) });
client.on("advertise", (channels) => {
  if (out.channelsAtConnect === null) {
    out.channelsAtConnect = channels.map((c) => c.topic);
    const clock = channels.find((x) => x.topic === "/clock");
    if (clock) client.subscribe(clock.id);
    return;
  }
  const s = channels.find((x) => x.topic === scanTopic);
  const d = channels.find((x) => x.topic === descriptionTopic);
  if (status.unadvertised) {
    if (s) {
      out.readvertised = channels.map((c) => c.topic);
      client.close();
      finish(0);
    }
    return;
  }
  for (const c of channels) out.advertised.push({ id: c.id, topic: c.topic, schemaName: c.schemaName });
  // the scan first: once the description arrives, the server has taken both subscriptions
  if (s && !scan) scan = subscribeTo(s);
  if (d && !description) description = subscribeTo(d);
});
client.on("message", ({ subscriptionId, data }) => {
  if (description && subscriptionId === description.subscription) {
    out.description = description.reader.readMessage(data).data;
    status.ready = scan !== null;
    writeStatus();
  } else if (scan && subscriptionId === scan.subscription) {
    if (status.unadvertised) {
      ++out.scansAfterUnadvertise;
      return;
    }
    const stamp = scan.reader.readMessage(data).header.stamp;
    out.scanStamps.push(stamp.sec * 1e9 + stamp.nanosec);
    status.scans = out.scanStamps.length;
    writeStatus();
  }
});
client.on("unadvertise", (ids) => {
  out.unadvertised.push(...ids);
  if (scan && ids.includes(scan.id)) {
    status.unadvertised = true;
    writeStatus();
  }
});
