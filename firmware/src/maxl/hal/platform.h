// Which hardware layer this build uses. Exactly one of:
//   MAXL_HAL_WASM     wasm32 for the simulator (imports from JS; WASM_ABI.md)
//   MAXL_HAL_ARDUINO  a real board, through the Arduino core
//   MAXL_HAL_HOST     the host tests (virtual clock, byte buffers, pin log)
// wasm comes first: the wasm Arduino shim may define ARDUINO for sketches.
#ifndef MAXL_HAL_PLATFORM_H
#define MAXL_HAL_PLATFORM_H

#if defined(__wasm__)
#define MAXL_HAL_WASM 1
#elif defined(ARDUINO)
#define MAXL_HAL_ARDUINO 1
#else
#define MAXL_HAL_HOST 1
#endif

#endif
