// Calls the Simulation Interfaces services the way Foxglove's Service Call panel does: the
// reference client's sendServiceCallRequest with the request's own encoding (json) and the
// JSON text a user types; answers are read from serviceCallResponse / serviceCallFailure.
// Prints one JSON object.
// Usage: node services_client.js ws://127.0.0.1:PORT MODE
//   calls      the services advertised, a sequence of good calls (pause, step 5, the robot's
//              state, ...) and bad ones (not JSON, wrong shape, unknown id, wrong encoding,
//              truncated frames)
//   nocontrol  a server without control: what serverInfo offers, and a call made anyway
//   vanish     a first connection calls and disconnects before its answer; a second one calls
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");

const [url, mode] = process.argv.slice(2);
const out = { serverInfo: null, services: null, results: {}, statuses: [], errors: [] };
const finish = (code) => {
  process.stdout.write(JSON.stringify(out) + "\n");
  process.exit(code);
};
setTimeout(() => {
  out.errors.push("timed out");
  finish(1);
}, 30000);

/// A connected client that remembers what the server offers and matches answers to calls.
function connect() {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    const client = new FoxgloveClient({ ws });
    const c = { ws, client, serverInfo: null, channels: null, services: null, waiting: new Map(), nextCall: 1, closed: null };
    client.on("error", (e) => out.errors.push(String(e && e.message ? e.message : e)));
    client.on("serverInfo", (info) => (c.serverInfo = info));
    client.on("status", (s) => out.statuses.push(s.message));
    client.on("advertiseServices", (services) => (c.services = services));
    client.on("serviceCallResponse", (r) => {
      const w = c.waiting.get(r.callId);
      if (!w) return out.errors.push(`response to unknown call ${r.callId}`);
      c.waiting.delete(r.callId);
      const text = new TextDecoder().decode(r.data);
      w({ kind: "response", serviceId: r.serviceId, callId: r.callId, encoding: r.encoding, value: JSON.parse(text) });
    });
    client.on("serviceCallFailure", (f) => {
      const w = c.waiting.get(f.callId);
      if (!w) return out.errors.push(`failure of unknown call ${f.callId}: ${f.message}`);
      c.waiting.delete(f.callId);
      w({ kind: "failure", serviceId: f.serviceId, callId: f.callId, message: f.message });
    });
    c.closed = new Promise((r) => client.on("close", r));
    // the channels come after serverInfo, the services (when offered) right after them
    client.on("advertise", (channels) => {
      if (c.channels) return;
      c.channels = channels;
      setImmediate(() => resolve(c));
    });
  });
}

/// Calls service `serviceId` with `data` (an object is sent as its JSON text); resolves with
/// the response or the failure.
function callId(c, serviceId, data, encoding = "json") {
  const callId = c.nextCall++;
  const bytes = typeof data === "string" ? new TextEncoder().encode(data) : new TextEncoder().encode(JSON.stringify(data));
  const answer = new Promise((resolve) => c.waiting.set(callId, resolve));
  c.client.sendServiceCallRequest({ serviceId, callId, encoding, data: bytes });
  return answer;
}
function call(c, name, data, encoding) {
  const s = c.services.find((x) => x.name === name);
  if (!s) throw new Error(`service ${name} not advertised`);
  return callId(c, s.id, data, encoding);
}

async function calls() {
  const c = await connect();
  // advertiseServices is sent right after advertise on connect: wait for it a moment
  for (let i = 0; i < 100 && !c.services; ++i) await new Promise((r) => setTimeout(r, 20));
  out.serverInfo = c.serverInfo;
  out.services = (c.services ?? []).map((s) => {
    const schemas = {};
    for (const k of ["request", "response"]) {
      try {
        schemas[k] = JSON.parse(s[k].schema).type;
      } catch (e) {
        schemas[k] = `unparsable: ${e.message}`;
      }
    }
    return { id: s.id, name: s.name, type: s.type,
             request: { ...s.request, schema: undefined }, response: { ...s.response, schema: undefined },
             schemaTypes: schemas, requestSchema: s.requestSchema ?? null };
  });
  const r = out.results;
  r.stateBefore = await call(c, "/get_simulation_state", {});
  r.pause = await call(c, "/set_simulation_state", { state: { state: 2 } });
  r.pauseAgain = await call(c, "/set_simulation_state", { state: { state: 2 } });
  r.step = await call(c, "/step_simulation", { steps: 5 });
  r.stateAfter = await call(c, "/get_simulation_state", {});
  r.robot = await call(c, "/get_entity_state", { entity: "robot" });
  r.nobody = await call(c, "/get_entity_state", { entity: "nobody" });
  r.entities = await call(c, "/get_entities", { filters: { filter: "rob.*", categories: [{ category: 1 }] } });
  r.teleport = await call(c, "/set_entity_state",
                          { entity: "robot", state: { pose: { position: { x: 2, y: 1, z: 0 }, orientation: { z: 0, w: 1 } } } });
  r.reset = await call(c, "/reset_simulation", {});
  r.features = await call(c, "/get_simulator_features", {});
  // bad calls: each answered with a serviceCallFailure
  r.badJson = await call(c, "/set_simulation_state", "{state:");
  r.wrongShape = await call(c, "/set_simulation_state", { state: 2 });
  r.unknownField = await call(c, "/step_simulation", { stepz: 5 });
  r.unknownId = await callId(c, 99, {});
  r.wrongEncoding = await call(c, "/get_simulation_state", {}, "cdr");
  // hand-made frames: an encoding length past the end (ids readable), and 5 bytes (no ids)
  const absurd = Buffer.from([0x02, 1, 0, 0, 0, 77, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, 0x7b, 0x7d]);
  r.truncated = await new Promise((resolve) => {
    c.waiting.set(77, resolve);
    c.ws.send(absurd);
  });
  const before = out.statuses.length;
  c.ws.send(Buffer.from([0x02, 1, 0, 0, 0]));
  // answered in order: a good call after it comes back after the status
  r.afterShort = await call(c, "/get_simulation_state", {});
  r.shortStatus = out.statuses.slice(before);
  c.client.close();
}

async function nocontrol() {
  const c = await connect();
  out.serverInfo = c.serverInfo;
  // a call anyway; its failure comes after any advertiseServices the server would have sent
  out.results.call = await callId(c, 1, {});
  out.services = c.services;
  c.client.close();
}

async function vanish() {
  const a = await connect();
  for (let i = 0; i < 100 && !a.services; ++i) await new Promise((r) => setTimeout(r, 20));
  out.services = (a.services ?? []).map((s) => s.name);
  // the first connection calls and goes; its answer must not reach anybody, nor break anything
  call(a, "/get_simulation_state", {}).then((x) => out.errors.push(`the closed connection got ${JSON.stringify(x)}`));
  a.client.close();
  await a.closed;
  const b = await connect();
  for (let i = 0; i < 100 && !b.services; ++i) await new Promise((r) => setTimeout(r, 20));
  out.results.second = await call(b, "/get_simulation_state", {});
  b.client.close();
}

({ calls, nocontrol, vanish })[mode]()
  .then(() => finish(0))
  .catch((e) => {
    out.errors.push(String(e && e.stack ? e.stack : e));
    finish(1);
  });
