#include "maxl/wire/protocol.h"

namespace maxl_fw {

const char* codecErrorName(CodecError e) {
  switch (e) {
    case CODEC_OK: return "OK";
    case CODEC_TOO_LONG: return "TOO_LONG";
    case CODEC_BAD_COBS: return "BAD_COBS";
    case CODEC_TOO_SHORT: return "TOO_SHORT";
    case CODEC_BAD_CRC: return "BAD_CRC";
    case CODEC_MALFORMED: return "MALFORMED";
    case CODEC_UNKNOWN_MESSAGE: return "UNKNOWN_MESSAGE";
  }
  return "?";
}

}  // namespace maxl_fw
