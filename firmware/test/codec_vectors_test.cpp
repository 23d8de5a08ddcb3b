// The shared vectors (docs/protocol.md, first paragraph): every frame decodes
// to its packet, every packet encodes to its frame, every bad frame gives its
// error. Runs over the TS-generated docs/protocol-vectors.json when present,
// and always over fixtures/hand-vectors.json (written from the spec by an
// independent Python encoder, fixtures/make_hand_vectors.py).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "maxl/wire/frame_receiver.h"
#include "maxl/wire/frame_writer.h"
#include "maxl/wire/messages.h"
#include "support/hex.h"

using nlohmann::json;
using namespace maxl_fw;
using maxltest::fromHex;
using maxltest::toHex;

namespace {

const std::map<std::string, uint8_t>& typeCodes() {
  static const std::map<std::string, uint8_t> m = {
      {"HELLO_REQUEST", type::HELLO_REQUEST}, {"PING", type::PING_REQUEST}, {"CLOCK", type::CLOCK},
      {"SUBSCRIBE", type::SUBSCRIBE}, {"GEOMETRY", type::GEOMETRY}, {"TIMING", type::TIMING},
      {"EVENTS", type::EVENTS}, {"REPLACE_TAIL", type::REPLACE_TAIL}, {"HALT", type::HALT},
      {"STATUS_REQUEST", type::STATUS_REQUEST}, {"HELLO", type::HELLO}, {"READER", type::READER},
      {"ACK", type::ACK}, {"NACK", type::NACK}, {"PONG", type::PONG}, {"STATUS", type::STATUS},
      {"SAMPLES", type::SAMPLES}};
  return m;
}
std::string typeName(uint8_t code) {
  for (auto& kv : typeCodes())
    if (kv.second == code) return kv.first;
  return "?";
}

msg::DecodeContext contextOf(const json& v) {
  msg::DecodeContext c{0, 0};
  if (v.contains("context")) {
    c.positionSlots = v["context"].value("positionSlots", 0);
    c.sampleChannels = v["context"].value("channels", 0);
  }
  return c;
}

// Frame -> packet -> the vectors' JSON form. Returns the error name, or "" and fills `out`.
std::string decodeFrame(const std::vector<uint8_t>& bytes, const msg::DecodeContext& ctx, json& out) {
  OwnedFrameReceiver rx;
  for (size_t i = 0; i < bytes.size(); i++) {
    FrameReceiver::Result r = rx.push(bytes[i], 0);
    if (r == FrameReceiver::ERROR) return codecErrorName(rx.error());
    if (r == FrameReceiver::PACKET) {
      if (i + 1 != bytes.size()) return "TRAILING_BYTES";
      const uint8_t* p = rx.payload();
      uint8_t n = rx.payloadLength();
      CodecError e = msg::checkPayload(rx.type(), p, n, ctx);
      if (e != CODEC_OK) return codecErrorName(e);
      json f = json::object();
      switch (rx.type()) {
        case type::HELLO_REQUEST: { msg::HelloRequest m; msg::parse(p, n, m); f = {{"protocol", m.protocol}}; break; }
        case type::PING_REQUEST: { msg::Ping m; msg::parse(p, n, m); f = {{"pingId", m.pingId}, {"replyAfter", m.replyAfter}}; break; }
        case type::CLOCK: {
          msg::Clock m; msg::parse(p, n, m);
          f = {{"deviceRef", m.deviceRef}, {"authorRef", m.authorRef}, {"ratePpb", m.ratePpb}};
          break;
        }
        case type::SUBSCRIBE: {
          msg::Subscribe m; msg::parse(p, n, m);
          f = {{"reader", m.reader}, {"kind", m.kind}, {"slot", m.slot}};
          break;
        }
        case type::GEOMETRY: {
          msg::GeometryView g; g.parse(p, n, ctx.positionSlots);
          f = {{"firstId", g.firstId}, {"count", g.count}, {"flags", g.flags}};
          if (g.hasP0()) {
            json p0 = json::array();
            for (uint8_t i = 0; i < ctx.positionSlots; i++) p0.push_back(g.p0(i));
            f["p0"] = p0;
          }
          json segs = json::array();
          for (uint8_t k = 0; k < g.count; k++) {
            json p1 = json::array();
            for (uint8_t i = 0; i < ctx.positionSlots; i++) p1.push_back(g.p1(k, i));
            segs.push_back({{"length", g.length(k)}, {"p1", p1}});
          }
          f["segments"] = segs;
          break;
        }
        case type::TIMING: {
          msg::TimingView t; t.parse(p, n);
          f = {{"firstId", t.firstId}, {"count", t.count}, {"flags", t.flags}, {"stopDecel", t.stopDecel}};
          if (t.hasStart()) f["start"] = t.start;
          json segs = json::array();
          msg::TimingSegment s;
          for (uint8_t k = 0; k < t.count; k++) {
            t.next(s);
            json d = json::array();
            for (uint8_t i = 0; i < s.phaseCount; i++) d.push_back(s.durations[i]);
            segs.push_back({{"shape", s.shape}, {"durations", d}, {"alpha", s.alpha}});
          }
          f["segments"] = segs;
          break;
        }
        case type::EVENTS: {
          msg::EventsView e; e.parse(p, n);
          f = {{"segmentId", e.segmentId}, {"slot", e.slot}, {"firstIndex", e.firstIndex}, {"count", e.count}};
          json entries = json::array();
          msg::EventEntry en;
          for (uint8_t k = 0; k < e.count; k++) {
            e.next(en);
            entries.push_back({{"offset", en.offset}, {"value", en.value}});
          }
          f["entries"] = entries;
          break;
        }
        case type::REPLACE_TAIL: { msg::ReplaceTail m; msg::parse(p, n, m); f = {{"fromId", m.fromId}}; break; }
        case type::HALT: { msg::Halt m; msg::parse(p, n, m); f = {{"mode", m.mode}, {"at", m.at}}; break; }
        case type::STATUS_REQUEST: break;
        case type::HELLO: {
          msg::Hello m; msg::parse(p, n, m);
          f = {{"protocol", m.protocol}, {"fwMajor", m.fwMajor}, {"fwMinor", m.fwMinor}, {"fwPatch", m.fwPatch},
               {"clockHz", m.clockHz}, {"segmentCapacity", m.segmentCapacity}, {"eventCapacity", m.eventCapacity},
               {"readerCount", m.readerCount}, {"name", std::string(m.name.text, m.name.length)}};
          break;
        }
        case type::READER: {
          msg::Reader m; msg::parse(p, n, m);
          f = {{"index", m.index}, {"kind", m.kind}, {"channels", m.channels},
               {"name", std::string(m.name.text, m.name.length)}};
          break;
        }
        case type::ACK: {
          msg::Ack m; msg::parse(p, n, m);
          f = {{"ackSeq", m.ackSeq}, {"freeSegments", m.freeSegments}, {"freeEvents", m.freeEvents}};
          break;
        }
        case type::NACK: {
          msg::Nack m; msg::parse(p, n, m);
          f = {{"seq", m.seq}, {"reason", m.reason}, {"detail", m.detail}};
          break;
        }
        case type::PONG: {
          msg::Pong m; msg::parse(p, n, m);
          f = {{"pingId", m.pingId}, {"rxTime", m.rxTime}, {"txTime", m.txTime}};
          break;
        }
        case type::STATUS: {
          msg::Status m; msg::parse(p, n, m);
          f = {{"now", m.now}, {"state", m.state}, {"segmentId", m.segmentId}, {"sigma", m.sigma},
               {"depth", m.depth}, {"flags", m.flags}};
          break;
        }
        case type::SAMPLES: {
          msg::SamplesView s; s.parse(p, n, ctx.sampleChannels);
          f = {{"reader", s.reader}, {"sampleSeq", s.sampleSeq}, {"count", s.count}, {"t0", s.t0}};
          json samples = json::array();
          for (uint8_t k = 0; k < s.count; k++) {
            uint32_t dt;
            float values[64];
            s.next(dt, values);
            json vs = json::array();
            for (uint8_t c = 0; c < ctx.sampleChannels; c++) vs.push_back(values[c]);
            samples.push_back({{"dt", dt}, {"values", vs}});
          }
          f["samples"] = samples;
          break;
        }
      }
      out = {{"seq", rx.seq()}, {"type", typeName(rx.type())}, {"fields", f}};
      return "";
    }
  }
  return "NO_FRAME";
}

// Packet JSON -> frame, through the library's writers.
std::vector<uint8_t> encodePacket(const json& packet, const msg::DecodeContext& ctx) {
  OwnedFrameWriter fw;
  const json& f = packet["fields"];
  uint8_t t = typeCodes().at(packet["type"].get<std::string>());
  ByteWriter& w = fw.begin(packet["seq"].get<uint8_t>(), t);
  auto name = [](const json& s, std::string& keep) {
    keep = s.get<std::string>();
    return msg::Name{keep.c_str(), (uint8_t)keep.size()};
  };
  std::string keep;
  switch (t) {
    case type::HELLO_REQUEST: msg::write(w, msg::HelloRequest{f["protocol"]}); break;
    case type::PING_REQUEST: msg::write(w, msg::Ping{f["pingId"], f["replyAfter"]}); break;
    case type::CLOCK: msg::write(w, msg::Clock{f["deviceRef"], f["authorRef"], f["ratePpb"]}); break;
    case type::SUBSCRIBE: msg::write(w, msg::Subscribe{f["reader"], f["kind"], f["slot"]}); break;
    case type::GEOMETRY: {
      std::vector<int32_t> p0, p1;
      std::vector<float> lengths;
      if (f.contains("p0")) p0 = f["p0"].get<std::vector<int32_t>>();
      for (auto& s : f["segments"]) {
        lengths.push_back(s["length"].get<float>());
        for (auto& v : s["p1"]) p1.push_back(v.get<int32_t>());
      }
      msg::writeGeometry(w, f["firstId"], f["count"], f["flags"], ctx.positionSlots, p0.data(), lengths.data(),
                         p1.data());
      break;
    }
    case type::TIMING: {
      std::vector<msg::TimingSegment> segs;
      for (auto& s : f["segments"]) {
        msg::TimingSegment ts{};
        ts.shape = s["shape"];
        auto d = s["durations"].get<std::vector<uint32_t>>();
        ts.phaseCount = (uint8_t)d.size();
        for (size_t i = 0; i < d.size() && i < 3; i++) ts.durations[i] = d[i];
        ts.alpha = s["alpha"].get<float>();
        segs.push_back(ts);
      }
      msg::writeTiming(w, f["firstId"], f["count"], f["flags"], f["stopDecel"].get<float>(), f.value("start", 0u),
                       segs.data());
      break;
    }
    case type::EVENTS: {
      std::vector<msg::EventEntry> entries;
      for (auto& e : f["entries"]) entries.push_back(msg::EventEntry{e["offset"], e["value"].get<float>()});
      msg::writeEvents(w, f["segmentId"], f["slot"], f["firstIndex"], f["count"], entries.data());
      break;
    }
    case type::REPLACE_TAIL: msg::write(w, msg::ReplaceTail{f["fromId"]}); break;
    case type::HALT: msg::write(w, msg::Halt{f["mode"], f["at"]}); break;
    case type::STATUS_REQUEST: break;
    case type::HELLO: {
      msg::Hello h{f["protocol"], f["fwMajor"], f["fwMinor"], f["fwPatch"], f["clockHz"], f["segmentCapacity"],
                   f["eventCapacity"], f["readerCount"], name(f["name"], keep)};
      msg::write(w, h);
      break;
    }
    case type::READER: msg::write(w, msg::Reader{f["index"], f["kind"], f["channels"], name(f["name"], keep)}); break;
    case type::ACK: msg::write(w, msg::Ack{f["ackSeq"], f["freeSegments"], f["freeEvents"]}); break;
    case type::NACK: msg::write(w, msg::Nack{f["seq"], f["reason"], f["detail"]}); break;
    case type::PONG: msg::write(w, msg::Pong{f["pingId"], f["rxTime"], f["txTime"]}); break;
    case type::STATUS:
      msg::write(w, msg::Status{f["now"], f["state"], f["segmentId"], f["sigma"].get<float>(), f["depth"], f["flags"]});
      break;
    case type::SAMPLES:
      msg::writeSamplesHeader(w, f["reader"], f["sampleSeq"], f["count"], f["t0"]);
      for (auto& s : f["samples"]) {
        w.varint(s["dt"].get<uint32_t>());
        for (auto& v : s["values"]) w.f32(v.get<float>());
      }
      break;
  }
  EXPECT_TRUE(fw.finish()) << "payload overflow";
  return std::vector<uint8_t>(fw.frame(), fw.frame() + fw.frameLength());
}

// Numbers compare as doubles (f32 values are exact), everything else exactly.
bool sameJson(const json& a, const json& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  if (a.type() != b.type()) return false;
  if (a.is_object()) {
    if (a.size() != b.size()) return false;
    for (auto it = a.begin(); it != a.end(); ++it)
      if (!b.contains(it.key()) || !sameJson(it.value(), b[it.key()])) return false;
    return true;
  }
  if (a.is_array()) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); i++)
      if (!sameJson(a[i], b[i])) return false;
    return true;
  }
  return a == b;
}

size_t runVectors(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  json file = json::parse(in);
  EXPECT_EQ(file["protocol"], 1);
  size_t n = 0;
  for (const json& v : file["vectors"]) {
    SCOPED_TRACE(path + ": " + v["name"].get<std::string>());
    std::vector<uint8_t> bytes = fromHex(v["frame"]);
    msg::DecodeContext ctx = contextOf(v);
    json decoded;
    std::string error = decodeFrame(bytes, ctx, decoded);
    if (v.contains("error")) {
      EXPECT_EQ(error, v["error"].get<std::string>());
    } else {
      EXPECT_EQ(error, "");
      EXPECT_TRUE(sameJson(decoded, v["packet"])) << "decoded " << decoded.dump() << "\nexpected " << v["packet"].dump();
      EXPECT_EQ(toHex(encodePacket(v["packet"], ctx)), v["frame"].get<std::string>());
    }
    n++;
  }
  return n;
}

}  // namespace

TEST(Vectors, HandWrittenFromTheSpec) { EXPECT_GE(runVectors(MAXL_HAND_VECTORS), 30u); }

TEST(Vectors, SharedWithTheTypeScriptCodec) {
  std::ifstream probe(MAXL_PROTOCOL_VECTORS);
  if (!probe.good()) GTEST_SKIP() << MAXL_PROTOCOL_VECTORS << " is not there yet (generated by the TS codec)";
  EXPECT_GT(runVectors(MAXL_PROTOCOL_VECTORS), 0u);
}
