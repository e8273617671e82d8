// Streaming base64 decoding for VTK XML binary data. VTK encodes an array's header and its data
// either as one stream or as separately padded streams back to back, with whitespace around and
// sometimes inside; decoding quantum by quantum, restarting after padding, reads all of these.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace sm::io {

class Base64Reader {
 public:
  explicit Base64Reader(std::string_view text, size_t pos = 0)
      : text_(text), start_(pos), pos_(pos) {}

  // Decodes exactly n bytes into out. False when the text ends, or holds a character that is not
  // base64, before n bytes are decoded.
  bool read(uint8_t* out, size_t n);
  // An upper bound on the bytes still decodable (to reject absurd sizes before allocating).
  size_t maxRemaining() const {
    return size_t(pendingCount_ - pendingPos_) + (text_.size() - pos_) / 4 * 3 + 3;
  }
  // After read returned false: where a character that is not base64 (or padding out of place)
  // stopped it, counted from where reading started (an appended array's offset); npos when the
  // text just ended.
  size_t badCharacter() const { return bad_ == std::string_view::npos ? bad_ : bad_ - start_; }
  char characterAt(size_t i) const { return text_[start_ + i]; }

 private:
  bool decodeQuantum(uint8_t* out, int& count);  // 1 to 3 bytes of the next quantum
  std::string_view text_;
  size_t start_, pos_;
  size_t bad_ = std::string_view::npos;
  uint8_t pending_[3] = {};
  int pendingCount_ = 0, pendingPos_ = 0;
};

}  // namespace sm::io
