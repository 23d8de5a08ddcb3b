#include "maxl/readers/reader.h"

MAXL_Reader* MAXL_Reader::head_ = 0;

MAXL_Reader::MAXL_Reader(const char* name, uint8_t kind, uint8_t channels)
    : name_(name), next_(0), kind_(kind), channels_(channels), slot_(0), subscribed_(false) {
  // Append, so that indices follow declaration order.
  MAXL_Reader** link = &head_;
  while (*link) link = &(*link)->next_;
  *link = this;
}

#if !defined(__AVR__)
MAXL_Reader::~MAXL_Reader() {
  MAXL_Reader** link = &head_;
  while (*link && *link != this) link = &(*link)->next_;
  if (*link) *link = next_;
}
#endif

uint8_t MAXL_Reader::index() const {
  uint8_t i = 0;
  for (const MAXL_Reader* r = head_; r && r != this; r = r->next_) i++;
  return i;
}

uint8_t MAXL_Reader::count() {
  uint8_t n = 0;
  for (const MAXL_Reader* r = head_; r; r = r->next_) n++;
  return n;
}

MAXL_Reader* MAXL_Reader::at(uint8_t index) {
  MAXL_Reader* r = head_;
  while (r && index--) r = r->next_;
  return r;
}

void MAXL_Reader::bind(uint8_t slot) {
  slot_ = slot;
  subscribed_ = true;
  onSubscribe();
}

void MAXL_Reader::unbind() {
  if (subscribed_) onUnsubscribe();
  subscribed_ = false;
  slot_ = 0;
}
