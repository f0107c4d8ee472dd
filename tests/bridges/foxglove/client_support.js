// What every test client of the Foxglove bridge starts with: the reference client
// (@foxglove/ws-protocol) connected to the server, its errors collected, and one JSON object
// printed when it finishes (or times out).
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");

/// Connects to `url`. `out` (which has an `errors` array) is what finish(code) prints, as one
/// JSON line, before it ends the process with `code`; after `timeoutMs` it finishes with
/// "timed out" and code 1. Returns { client, finish }.
function startClient(url, out, timeoutMs) {
  const finish = (code) => {
    process.stdout.write(JSON.stringify(out) + "\n");
    process.exit(code);
  };
  setTimeout(() => {
    out.errors.push("timed out");
    finish(1);
  }, timeoutMs);
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  client.on("error", (e) => out.errors.push(String(e && e.message ? e.message : e)));
  return { client, finish };
}

module.exports = { startClient };
