// Houdini's JSON layer: decoding binary JSON (the token stream of .bgeo files) into a JSON tree, and
// writing one JSON document as text (.geo) or as binary JSON (.bgeo).
#pragma once
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace weft::io {

// True when `bytes` start with 0x7f and the binary JSON magic, in either byte order.
bool is_binary_json(std::string_view bytes);

// Decodes a whole binary JSON document. Uniform arrays become plain JSON arrays, integers become int64 and
// reals double. Errors are FormatErrors naming `path` and the byte offset.
nlohmann::json decode_binary_json(std::string_view bytes, const std::string& path);

// Streams one JSON document. Values are emitted in order; inside a map, strings alternate as keys and
// values. Binary output is little-endian and stores numeric arrays packed at their element width.
class JsonWriter {
 public:
  enum class Format { Text, Binary };
  enum class Packing { Int8, Int16, Int32, Int64, UInt8, Real32, Real64 };

  JsonWriter(std::ostream& out, Format format);
  Format format() const { return format_; }

  void begin_array();
  void end_array();
  void begin_map();
  void end_map();
  void string(std::string_view s);
  void boolean(bool b);
  void integer(int64_t v);
  void real(double v);
  // An array of numbers; text prints Real32 values at float precision.
  void numbers(const double* v, size_t n, Packing packing);
  void numbers(const int64_t* v, size_t n, Packing packing);

 private:
  void before_value();
  void put(uint8_t b) { out_.put(static_cast<char>(b)); }
  void put_le(uint64_t v, int bytes);
  void put_length(uint64_t n);
  void put_text(std::string_view s) { out_.write(s.data(), static_cast<std::streamsize>(s.size())); }
  template <class T>
  void put_number_text(T v);
  template <class T>
  void packed(const T* v, size_t n, Packing packing);

  std::ostream& out_;
  Format format_;
  std::vector<std::pair<bool, size_t>> open_;  // per open container: is it a map, values written so far
};

}  // namespace weft::io
