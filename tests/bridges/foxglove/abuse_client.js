// Clients that misbehave, next to one that behaves: raw `ws` connections send garbage, unknown
// ops and channels, truncated and oversize frames, non-finite and wrong-size commands, and
// offer the wrong subprotocol; a slow client subscribes to the cameras and stops reading. A
// well-behaved FoxgloveClient keeps counting /scan messages meanwhile. Prints one JSON object.
// Usage: node abuse_client.js ws://127.0.0.1:PORT [slow_seconds]
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");

const url = process.argv[2];
const slowSeconds = Number(process.argv[3] ?? 6);
const PROTO = "foxglove.websocket.v1";
const out = { refusals: {}, replies: [], afterAbuse: null, watcher: { scans: [], closed: false }, slow: null, errors: [] };

function finish(code) {
  process.stdout.write(JSON.stringify(out) + "\n");
  process.exit(code);
}
setTimeout(() => {
  out.errors.push("timed out");
  finish(1);
}, 40000);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/// Opens a connection offering `protocols`; resolves with the HTTP status when refused.
function tryHandshake(protocols) {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, protocols);
    ws.on("unexpected-response", (req, res) => {
      let body = "";
      res.on("data", (d) => (body += d));
      res.on("end", () => resolve({ status: res.statusCode, body }));
    });
    ws.on("open", () => {
      resolve({ status: 101, protocol: ws.protocol });
      ws.close();
    });
    ws.on("error", (e) => resolve({ error: e.message }));
  });
}

/// Opens a connection and keeps it open; resolves with the HTTP status (101 when accepted).
function holdHandshake() {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, [PROTO]);
    ws.on("unexpected-response", (req, res) => {
      res.resume();
      resolve({ status: res.statusCode, ws: null });
    });
    ws.on("open", () => resolve({ status: 101, ws }));
    ws.on("error", (e) => resolve({ error: e.message, ws: null }));
  });
}

/// A raw protocol connection that collects JSON replies and binary message data.
function rawClient() {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(url, [PROTO]);
    const c = { ws, json: [], data: [], channels: new Map(), waiters: [] };
    ws.on("message", (data, isBinary) => {
      if (isBinary) {
        c.data.push(data);
        return;
      }
      const m = JSON.parse(data.toString());
      if (m.op === "advertise") for (const ch of m.channels) c.channels.set(ch.topic, ch);
      c.json.push(m);
      for (const w of c.waiters.splice(0)) w();
    });
    ws.on("open", () => resolve(c));
    ws.on("error", reject);
  });
}

/// Sends one frame and waits for the next status reply (or gives up after `ms`).
async function expectStatus(c, label, frame, ms = 3000) {
  const before = c.json.filter((m) => m.op === "status").length;
  c.ws.send(frame);
  const deadline = Date.now() + ms;
  while (Date.now() < deadline) {
    const statuses = c.json.filter((m) => m.op === "status");
    if (statuses.length > before) {
      out.replies.push({ label, level: statuses[before].level, message: statuses[before].message });
      return;
    }
    await new Promise((r) => {
      c.waiters.push(r);
      setTimeout(r, 50);
    });
  }
  out.replies.push({ label, level: null, message: "no status reply" });
}

function clientData(channel, payload) {
  const b = Buffer.alloc(5 + payload.length);
  b.writeUInt8(0x01, 0);
  b.writeUInt32LE(channel, 1);
  Buffer.from(payload).copy(b, 5);
  return b;
}

/// geometry_msgs/Twist in XCDR1 little endian: encapsulation header, then six float64.
function twistCdr(values) {
  const b = Buffer.alloc(4 + 48);
  b.writeUInt8(0x00, 0);
  b.writeUInt8(0x01, 1);
  values.forEach((v, i) => b.writeDoubleLE(v, 4 + 8 * i));
  return b;
}

async function main() {
  // 1. the handshake: wrong or missing subprotocol is refused, the right one accepted
  out.refusals.wrong = await tryHandshake(["not.foxglove.v0"]);
  out.refusals.none = await tryHandshake([]);
  out.refusals.right = await tryHandshake([PROTO]);

  // 2. a well-behaved client, counting scans throughout
  const watcherWs = new WebSocket(url, [PROTO]);
  const watcher = new FoxgloveClient({ ws: watcherWs });
  watcher.on("advertise", (list) => {
    const scan = list.find((c) => c.topic === "/scan");
    if (scan) watcher.subscribe(scan.id);
  });
  watcher.on("message", () => out.watcher.scans.push(Date.now()));
  watcher.on("close", () => (out.watcher.closed = true));

  // 3. a slow client: subscribes to every camera topic, then stops reading its socket
  const slow = await rawClient();
  await sleep(300);
  let id = 0;
  const cams = [...slow.channels.values()].filter((c) => /image|points/.test(c.topic));
  slow.ws.send(JSON.stringify({ op: "subscribe", subscriptions: cams.map((c) => ({ id: id++, channelId: c.id })) }));
  await sleep(300);
  slow.ws._socket.pause();
  const slowStart = Date.now();

  // 4. abuse, one frame at a time, each answered by a status message
  const bad = await rawClient();
  await sleep(300);
  await expectStatus(bad, "garbage text", "this is not JSON {{{");
  await expectStatus(bad, "not an object", "[1,2,3]");
  await expectStatus(bad, "unknown op", JSON.stringify({ op: "frobnicate" }));
  await expectStatus(bad, "unsupported op", JSON.stringify({ op: "getParameters", parameterNames: [] }));
  await expectStatus(bad, "bad subscribe field", JSON.stringify({ op: "subscribe", subscriptions: [{ id: -1, channelId: "x" }] }));
  await expectStatus(bad, "unknown channel subscribe", JSON.stringify({ op: "subscribe", subscriptions: [{ id: 1, channelId: 99999 }] }));
  await expectStatus(bad, "unknown subscription", JSON.stringify({ op: "unsubscribe", subscriptionIds: [42] }));
  await expectStatus(bad, "empty binary", Buffer.alloc(0));
  await expectStatus(bad, "short binary", Buffer.from([0x01, 0x05]));
  await expectStatus(bad, "unknown opcode", Buffer.from([0x07, 0, 0, 0, 0]));
  await expectStatus(bad, "unknown client channel", clientData(77, [1, 2, 3]));
  await expectStatus(bad, "oversize text", "x".repeat(2 * 1024 * 1024));
  await expectStatus(bad, "oversize binary", clientData(1, Buffer.alloc(1536 * 1024)));
  await expectStatus(bad, "advertise foreign topic",
    JSON.stringify({ op: "advertise", channels: [{ id: 5, topic: "/not_ours", encoding: "cdr", schemaName: "std_msgs/msg/String" }] }));
  await expectStatus(bad, "advertise wrong schema",
    JSON.stringify({ op: "advertise", channels: [{ id: 6, topic: "/cmd_vel", encoding: "cdr", schemaName: "std_msgs/msg/String" }] }));
  await expectStatus(bad, "advertise bad encoding",
    JSON.stringify({ op: "advertise",
                     channels: [{ id: 7, topic: "/cmd_vel", encoding: "protobuf", schemaName: "geometry_msgs/msg/Twist" }] }));
  // advertisements that are fine get no reply; commands on them do when they are bad
  bad.ws.send(JSON.stringify({ op: "advertise", channels: [
    { id: 1, topic: "/cmd_vel", encoding: "cdr", schemaName: "geometry_msgs/msg/Twist" },
    { id: 2, topic: "/head/command", encoding: "json", schemaName: "std_msgs/msg/Float64MultiArray" },
    { id: 3, topic: "/cmd_vel", encoding: "json", schemaName: "geometry_msgs/Twist" }] }));
  await sleep(200);
  await expectStatus(bad, "nan twist", clientData(1, twistCdr([NaN, 0, 0, 0, 0, 0])));
  await expectStatus(bad, "inf twist", clientData(1, twistCdr([0, 0, 0, 0, 0, Infinity])));
  await expectStatus(bad, "truncated cdr twist", clientData(1, twistCdr([0.1, 0, 0, 0, 0, 0]).subarray(0, 30)));
  await expectStatus(bad, "json twist not json", clientData(3, Buffer.from("{linear:")));
  await expectStatus(bad, "json twist wrong type", clientData(3, Buffer.from(JSON.stringify({ linear: { x: "fast" } }))));
  await expectStatus(bad, "head wrong size", clientData(2, Buffer.from(JSON.stringify({ data: [0.1] }))));
  await expectStatus(bad, "head non-number", clientData(2, Buffer.from(JSON.stringify({ data: [0.1, null, 0, 0] }))));
  // a good JSON twist is accepted silently
  bad.ws.send(clientData(3, Buffer.from(JSON.stringify({ linear: { x: 0.0, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0 } }))));

  // 5. a crowd: with the watcher, the slow and the bad client open, 13 of 20 more fit (16 at most)
  const crowd = await Promise.all([...Array(20)].map(() => holdHandshake()));
  out.crowd = { accepted: crowd.filter((c) => c.status === 101).length, refused: crowd.filter((c) => c.status === 503).length };
  for (const c of crowd) if (c.ws) c.ws.close();
  await sleep(300);

  // 6. the abusive connection still works: subscribe to /scan and get data
  const scan = bad.channels.get("/scan");
  const dataBefore = bad.data.length;
  bad.ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: 100, channelId: scan.id }] }));
  await sleep(800);
  // message data (opcode 1) for subscription 100, not time frames (opcode 2)
  const scans = bad.data.slice(dataBefore).filter((d) => d[0] === 0x01 && d.readUInt32LE(1) === 100);
  out.afterAbuse = { open: bad.ws.readyState === WebSocket.OPEN, messages: scans.length };
  bad.ws.close();

  // 7. the slow client stays stalled for a while; then look at what it had been told
  const left = slowSeconds * 1000 - (Date.now() - slowStart);
  if (left > 0) await sleep(left);
  out.watcherStart = out.watcher.scans[0] ?? null;
  slow.ws._socket.resume();
  await sleep(1500);
  out.slow = {
    open: slow.ws.readyState === WebSocket.OPEN,
    subscribed: cams.map((c) => c.topic),
    warnings: slow.json.filter((m) => m.op === "status" && m.level === 1).map((m) => m.message),
    received: slow.data.length,
  };
  slow.ws.close();
  watcher.close();
  finish(0);
}

main().catch((e) => {
  out.errors.push(String(e && e.stack ? e.stack : e));
  finish(1);
});
