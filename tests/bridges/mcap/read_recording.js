// Reads an MCAP recording with the reference npm clients and prints what they saw as JSON, for
// the gtest in recording_js_test.cpp to check against figures computed by hand.
//   node read_recording.js FILE            indexed read: McapIndexedReader (@mcap/core) over a
//                                          @mcap/nodejs file handle, zstd/lz4 from @mcap/support,
//                                          every message decoded with @foxglove/rosmsg (ros2) +
//                                          @foxglove/rosmsg2-serialization
//   node read_recording.js FILE --stream   McapStreamReader over the bytes (works on a cut file)
// Errors are printed as {"error": "..."} with exit code 0, so the caller can check their text.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { loadDecompressHandlers } = require("@mcap/support");
const { crc32 } = require("@foxglove/crc");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const text = (bytes) => new TextDecoder().decode(bytes);

async function indexed(file, decompressHandlers) {
  const handle = await fs.promises.open(file, "r");
  try {
    const reader = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(handle), decompressHandlers });
    const out = {
      header: reader.header,
      chunks: reader.chunkIndexes.length,
      compression: [...new Set(reader.chunkIndexes.map((c) => c.compression))],
      statistics: {
        messageCount: Number(reader.statistics.messageCount),
        chunkCount: reader.statistics.chunkCount,
        channelCount: reader.statistics.channelCount,
        schemaCount: reader.statistics.schemaCount,
        startTime: Number(reader.statistics.messageStartTime),
        endTime: Number(reader.statistics.messageEndTime),
      },
      summaryOffsets: [...reader.summaryOffsetsByOpcode.keys()].sort((a, b) => a - b),
    };
    // the data-section CRC is not checked by McapIndexedReader itself: check it here
    const bytes = fs.readFileSync(file);
    const computed = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
    out.dataSectionCrc = { stored: reader.dataSectionCrc ?? 0, computed };

    // every channel: its schema, the count the statistics give and the count read and decoded
    const readers = new Map();
    const channels = {};
    for (const [id, ch] of reader.channelsById) {
      const schema = reader.schemasById.get(ch.schemaId);
      channels[ch.topic] = {
        id,
        messageEncoding: ch.messageEncoding,
        schemaName: schema.name,
        schemaEncoding: schema.encoding,
        qos: ch.metadata.get("offered_qos_profiles") ?? "",
        statistics: Number(reader.statistics.channelMessageCounts.get(id) ?? 0n),
        read: 0,
        decodeErrors: 0,
        firstError: "",
      };
      readers.set(id, new MessageReader(parse(text(schema.data), { ros2: true })));
    }
    // chunk CRCs are checked as each chunk is read (validateCrcs defaults to true; said here)
    let lastLogTime = -1n;
    out.logTimesInOrder = true;
    out.scans = [];
    for await (const m of reader.readMessages({ validateCrcs: true })) {
      const ch = reader.channelsById.get(m.channelId);
      const c = channels[ch.topic];
      c.read += 1;
      if (m.logTime < lastLogTime) out.logTimesInOrder = false;
      lastLogTime = m.logTime;
      let decoded;
      try {
        decoded = readers.get(m.channelId).readMessage(m.data);
      } catch (e) {
        c.decodeErrors += 1;
        if (!c.firstError) c.firstError = String(e.message ?? e);
        continue;
      }
      if (ch.topic === "/scan") {
        out.scans.push({
          sequence: m.sequence,
          logTime: Number(m.logTime),
          publishTime: Number(m.publishTime),
          stamp: decoded.header.stamp.sec * 1e9 + decoded.header.stamp.nanosec,
          frameId: decoded.header.frame_id,
          ranges: decoded.ranges.length,
          angleMin: decoded.angle_min,
          angleMax: decoded.angle_max,
          angleIncrement: decoded.angle_increment,
        });
      }
    }
    out.channels = channels;
    out.metadata = {};
    for await (const md of reader.readMetadata()) out.metadata[md.name] = Object.fromEntries(md.metadata);
    out.attachments = {};
    for await (const a of reader.readAttachments()) out.attachments[a.name] = { mediaType: a.mediaType, bytes: a.data.length };
    return out;
  } finally {
    await handle.close();
  }
}

function stream(file, decompressHandlers) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(fs.readFileSync(file));
  const out = { messages: 0, chunksComplete: 0, footer: false, error: "" };
  try {
    for (let r; (r = reader.nextRecord()); ) {
      if (r.type === "Message") out.messages += 1;
      if (r.type === "Footer") out.footer = true;
    }
  } catch (e) {
    out.error = String(e.message ?? e);
  }
  out.done = reader.done();
  return out;
}

(async () => {
  const [file, mode] = process.argv.slice(2);
  const decompressHandlers = await loadDecompressHandlers();
  let out;
  try {
    out = mode === "--stream" ? stream(file, decompressHandlers) : await indexed(file, decompressHandlers);
  } catch (e) {
    out = { error: String(e.message ?? e) };
  }
  // Exit as soon as the line is out. Left to end on its own, node waited for something it still
  // held (most likely the wasm decompressors' background compilation). One CI run on a busy
  // 2-core machine printed the right answer and then sat there until `timeout 120` killed it.
  process.stdout.write(JSON.stringify(out, (k, v) => (typeof v === "bigint" ? Number(v) : v)) + "\n", () => process.exit(0));
})();
