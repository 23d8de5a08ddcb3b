// Base of every reader (protocol §4 "Reader kinds"), and their registry.
//
// A reader is a static object in the sketch. Its constructor links it into a
// list (no heap), in declaration order; its index in that list is its index
// in the device's READER messages. It is bound to a track only when the
// author SUBSCRIBEs it, and unbound at every new session.
#ifndef MAXL_READERS_READER_H
#define MAXL_READERS_READER_H

#include <stdint.h>

class MAXL_Device;

class MAXL_Reader {
 public:
  const char* name() const { return name_; }
  uint8_t kind() const { return kind_; }
  uint8_t channels() const { return channels_; }
  bool subscribed() const { return subscribed_; }
  uint8_t slot() const { return slot_; }
  uint8_t index() const;

  static MAXL_Reader* first() { return head_; }
  MAXL_Reader* next() const { return next_; }
  static uint8_t count();
  static MAXL_Reader* at(uint8_t index);

 protected:
  MAXL_Reader(const char* name, uint8_t kind, uint8_t channels);
#if !defined(__AVR__)
  // Unlinks (readers that live on a test's stack). A sketch's readers are
  // static and live as long as the board runs, so on AVR there is none: with
  // it, every static reader's destruction would be compiled in, for an exit()
  // that never comes (~130-180 bytes of flash).
  ~MAXL_Reader();
#endif

  // Called by the device:
  virtual void onBegin() {}             // once, from MAXL_Device::begin()
  virtual void onSubscribe() {}         // bound to `slot()`
  virtual void onUnsubscribe() {}       // a new session dropped the binding
  virtual void onTick(MAXL_Device&) {}  // every loop() while subscribed
  virtual void onEventValue(float) {}   // event readers: a change on their slot

 private:
  friend class MAXL_Device;
  void bind(uint8_t slot);
  void unbind();

  static MAXL_Reader* head_;
  const char* name_;
  MAXL_Reader* next_;
  uint8_t kind_;
  uint8_t channels_;
  uint8_t slot_;
  bool subscribed_;

  MAXL_Reader(const MAXL_Reader&);             // not copyable: it is linked
  MAXL_Reader& operator=(const MAXL_Reader&);
};

#endif
