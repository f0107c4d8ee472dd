// Connects and subscribes to /clock (so the server sees a subscriber), waits for TOPIC to be
// advertised (it may appear after the connection), subscribes, decodes the first message of
// it and prints one JSON object.
// Usage: node late_topic_client.js ws://127.0.0.1:PORT TOPIC
"use strict";
const { startClient } = require("./client_support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [url, topic] = process.argv.slice(2);
const out = { channelsAtConnect: null, advertisedLater: false, channel: null, message: null, errors: [] };
const { client, finish } = startClient(url, out, 20000);
let reader = null;
let wanted = null;
client.on("advertise", (channels) => {
  if (out.channelsAtConnect === null) {
    out.channelsAtConnect = channels.map((c) => c.topic);
    const clock = channels.find((x) => x.topic === "/clock");
    if (clock) client.subscribe(clock.id);
  } else {
    out.advertisedLater = true;
  }
  const c = channels.find((x) => x.topic === topic);
  if (!c || reader) return;
  out.channel = { id: c.id, encoding: c.encoding, schemaName: c.schemaName };
  reader = new MessageReader(parse(c.schema, { ros2: true }));
  wanted = client.subscribe(c.id);
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  if (subscriptionId !== wanted) return;
  out.message = { receive: Number(timestamp), value: reader.readMessage(data) };
  client.close();
  finish(0);
});
