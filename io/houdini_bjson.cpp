// Binary JSON as Houdini's UT_JSONParser / UT_JSONWriter define it (UT_JSONDefines.h): one-byte tokens, then
// their data in the byte order the magic announces.
#include "io/houdini_bjson.hpp"
#include "io/trimesh.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace weft::io {

namespace {

using json = nlohmann::json;

constexpr uint8_t kNull = 0x00, kMapBegin = 0x7b, kMapEnd = 0x7d, kArrayBegin = 0x5b, kArrayEnd = 0x5d;
constexpr uint8_t kBool = 0x10, kInt8 = 0x11, kInt16 = 0x12, kInt32 = 0x13, kInt64 = 0x14;
constexpr uint8_t kUInt8 = 0x21, kUInt16 = 0x22, kReal16 = 0x18, kReal32 = 0x19, kReal64 = 0x1a;
constexpr uint8_t kString = 0x27, kFalse = 0x30, kTrue = 0x31;
constexpr uint8_t kTokenDef = 0x2b, kTokenRef = 0x26, kTokenUndef = 0x2d, kUniformArray = 0x40;
constexpr uint8_t kKeySeparator = 0x3a, kValueSeparator = 0x2c, kMagic = 0x7f;
constexpr std::string_view kMagicLittle = "NSJb", kMagicBig = "bJSN";

// Bytes of a numeric token's data; 0 for tokens that are not numbers.
size_t number_width(uint8_t tag) {
  switch (tag) {
    case kInt8:
    case kUInt8:
      return 1;
    case kInt16:
    case kUInt16:
    case kReal16:
      return 2;
    case kInt32:
    case kReal32:
      return 4;
    case kInt64:
    case kReal64:
      return 8;
    default:
      return 0;
  }
}

double half_to_double(uint16_t h) {
  const int exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  double v;
  if (exponent == 0)
    v = std::ldexp(mantissa, -24);
  else if (exponent == 31)
    v = mantissa ? std::nan("") : HUGE_VAL;
  else
    v = std::ldexp(mantissa + 1024, exponent - 25);
  return (h & 0x8000) ? -v : v;
}

std::string hex(uint8_t b) {
  const char* digits = "0123456789abcdef";
  return std::string("0x") + digits[b >> 4] + digits[b & 15];
}

class Decoder {
 public:
  Decoder(std::string_view bytes, const std::string& path) : b_(bytes), path_(path) {}

  json document() {
    if (!is_binary_json(b_)) fail(0, "no binary JSON magic (0x7f 'NSJb')");
    little_ = b_.substr(1, 4) == kMagicLittle;
    pos_ = 5;
    json root = value();
    skip_meta();
    if (pos_ != b_.size()) fail(pos_, "data after the end of the document");
    return root;
  }

 private:
  [[noreturn]] void fail(size_t at, const std::string& what) const {
    throw FormatError(path_ + ": byte " + std::to_string(at) + ": " + what);
  }
  void need(size_t n, const char* what) const {
    if (b_.size() - pos_ < n) fail(pos_, std::string("the file ends inside ") + what);
  }
  uint8_t byte(const char* what) {
    need(1, what);
    return static_cast<uint8_t>(b_[pos_++]);
  }
  uint64_t unsigned_bytes(size_t n, const char* what) {
    need(n, what);
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v |= uint64_t(static_cast<uint8_t>(b_[pos_ + (little_ ? i : n - 1 - i)])) << (8 * i);
    pos_ += n;
    return v;
  }
  // Lengths and token ids: one byte below 0xf1, else 0xf2 / 0xf4 / 0xf8 then 2 / 4 / 8 bytes.
  uint64_t length(const char* what) {
    const size_t at = pos_;
    const uint8_t c = byte(what);
    if (c < 0xf1) return c;
    if (c == 0xf2 || c == 0xf4 || c == 0xf8) return unsigned_bytes(c - 0xf0, what);
    fail(at, "invalid length prefix " + hex(c) + " in " + what);
  }
  std::string text(const char* what) {
    const uint64_t n = length(what);
    need(n, what);
    std::string s(b_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  json token(size_t at) {
    const uint64_t id = length("a token reference");
    const auto it = tokens_.find(id);
    if (it == tokens_.end()) fail(at, "reference to undefined token " + std::to_string(id));
    return it->second;
  }
  json number(uint8_t tag) {
    const uint64_t u = unsigned_bytes(number_width(tag), "a number");
    switch (tag) {
      case kInt8:
        return int64_t(int8_t(u));
      case kInt16:
        return int64_t(int16_t(u));
      case kInt32:
        return int64_t(int32_t(u));
      case kInt64:
        return int64_t(u);
      case kUInt8:
      case kUInt16:
        return int64_t(u);
      case kReal16:
        return half_to_double(uint16_t(u));
      case kReal32: {
        const uint32_t u32 = uint32_t(u);
        float f;
        std::memcpy(&f, &u32, 4);
        return double(f);
      }
      default: {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
      }
    }
  }
  // Token definitions carry no value; separators are a parsing aid that writers may emit.
  void skip_meta() {
    while (pos_ < b_.size()) {
      const uint8_t c = static_cast<uint8_t>(b_[pos_]);
      if (c == kTokenDef) {
        ++pos_;
        const uint64_t id = length("a token definition");
        tokens_[id] = text("a token definition");
      } else if (c == kTokenUndef) {
        ++pos_;
        tokens_.erase(length("a token undefinition"));
      } else if (c == kKeySeparator || c == kValueSeparator) {
        ++pos_;
      } else {
        return;
      }
    }
  }
  bool closes(uint8_t end, const char* what) {
    skip_meta();
    need(1, what);
    if (static_cast<uint8_t>(b_[pos_]) != end) return false;
    ++pos_;
    return true;
  }
  json uniform_array(size_t at) {
    const uint8_t type = byte("a uniform array");
    const uint64_t n = length("a uniform array");
    json a = json::array();
    auto& items = a.get_ref<json::array_t&>();
    if (type == kBool) {  // packed in 32-bit words, bit i of word i / 32
      need((n + 31) / 32 * 4, "a uniform bool array");
      uint32_t word = 0;
      for (uint64_t i = 0; i < n; ++i) {
        if (i % 32 == 0) word = uint32_t(unsigned_bytes(4, "a uniform bool array"));
        items.push_back(((word >> (i % 32)) & 1) != 0);
      }
    } else if (type == kString) {
      for (uint64_t i = 0; i < n; ++i) items.push_back(text("a uniform string array"));
    } else if (type == kTokenRef) {
      for (uint64_t i = 0; i < n; ++i) items.push_back(token(pos_));
    } else if (const size_t w = number_width(type)) {
      if (n > (b_.size() - pos_) / w)
        fail(at, "the file ends inside a uniform array of " + std::to_string(n) + " numbers");
      items.reserve(n);
      for (uint64_t i = 0; i < n; ++i) items.push_back(number(type));
    } else {
      fail(at, "uniform array of invalid element type " + hex(type));
    }
    return a;
  }
  json value() {
    skip_meta();
    const size_t at = pos_;
    const uint8_t tag = byte("a value");
    switch (tag) {
      case kNull:
        return nullptr;
      case kFalse:
        return false;
      case kTrue:
        return true;
      case kBool:
        return byte("a bool") != 0;
      case kString:
        return text("a string");
      case kTokenRef:
        return token(at);
      case kUniformArray:
        return uniform_array(at);
      case kArrayBegin: {
        json a = json::array();
        while (!closes(kArrayEnd, "an array")) a.push_back(value());
        return a;
      }
      case kMapBegin: {
        json m = json::object();
        while (!closes(kMapEnd, "a map")) {
          skip_meta();
          const size_t key_at = pos_;
          json key = value();
          if (!key.is_string()) fail(key_at, "map key is not a string");
          m[key.get<std::string>()] = value();
        }
        return m;
      }
      default:
        if (number_width(tag)) return number(tag);
        fail(at, "unexpected token " + hex(tag));
    }
  }

  std::string_view b_;
  const std::string& path_;
  size_t pos_ = 0;
  bool little_ = true;
  std::unordered_map<uint64_t, std::string> tokens_;
};

uint8_t packing_tag(JsonWriter::Packing p) {
  switch (p) {
    case JsonWriter::Packing::Int8:
      return kInt8;
    case JsonWriter::Packing::Int16:
      return kInt16;
    case JsonWriter::Packing::Int32:
      return kInt32;
    case JsonWriter::Packing::Int64:
      return kInt64;
    case JsonWriter::Packing::UInt8:
      return kUInt8;
    case JsonWriter::Packing::Real32:
      return kReal32;
    default:
      return kReal64;
  }
}

template <class T>
uint64_t packed_bits(T v, JsonWriter::Packing p) {
  if (p == JsonWriter::Packing::Real32) {
    const float f = static_cast<float>(v);
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
  }
  if (p == JsonWriter::Packing::Real64) {
    const double d = static_cast<double>(v);
    uint64_t u;
    std::memcpy(&u, &d, 8);
    return u;
  }
  return static_cast<uint64_t>(static_cast<int64_t>(v));
}

}  // namespace

bool is_binary_json(std::string_view bytes) {
  return bytes.size() >= 5 && static_cast<uint8_t>(bytes[0]) == kMagic &&
         (bytes.substr(1, 4) == kMagicLittle || bytes.substr(1, 4) == kMagicBig);
}

json decode_binary_json(std::string_view bytes, const std::string& path) { return Decoder(bytes, path).document(); }

JsonWriter::JsonWriter(std::ostream& out, Format format) : out_(out), format_(format) {
  if (format_ == Format::Binary) {
    put(kMagic);
    put_text(kMagicLittle);
  }
}

void JsonWriter::before_value() {
  if (open_.empty()) return;
  auto& [is_map, n] = open_.back();
  if (format_ == Format::Text) {
    if (n > 0) put(is_map && n % 2 == 1 ? ':' : ',');
    if (open_.size() == 1 && n % 2 == 0) put('\n');  // one key and value per line at the top level
  }
  ++n;
}

void JsonWriter::begin_array() {
  before_value();
  put(format_ == Format::Text ? '[' : kArrayBegin);
  open_.push_back({false, 0});
}

void JsonWriter::end_array() {
  open_.pop_back();
  if (format_ == Format::Text && open_.empty()) put('\n');
  put(format_ == Format::Text ? ']' : kArrayEnd);
}

void JsonWriter::begin_map() {
  before_value();
  put(format_ == Format::Text ? '{' : kMapBegin);
  open_.push_back({true, 0});
}

void JsonWriter::end_map() {
  open_.pop_back();
  put(format_ == Format::Text ? '}' : kMapEnd);
}

void JsonWriter::string(std::string_view s) {
  before_value();
  if (format_ == Format::Binary) {
    put(kString);
    put_length(s.size());
    put_text(s);
    return;
  }
  put('"');
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      put('\\');
      put(c);
    } else if (c == '\n') {
      put_text("\\n");
    } else if (c == '\t') {
      put_text("\\t");
    } else if (c < 0x20) {
      const char* digits = "0123456789abcdef";
      put_text("\\u00");
      put(digits[c >> 4]);
      put(digits[c & 15]);
    } else {
      put(c);
    }
  }
  put('"');
}

void JsonWriter::boolean(bool b) {
  before_value();
  if (format_ == Format::Text)
    put_text(b ? "true" : "false");
  else
    put(b ? kTrue : kFalse);
}

void JsonWriter::integer(int64_t v) {
  before_value();
  if (format_ == Format::Text) return put_number_text(v);
  if (v >= INT8_MIN && v <= INT8_MAX) {
    put(kInt8);
    put_le(uint64_t(v), 1);
  } else if (v >= INT16_MIN && v <= INT16_MAX) {
    put(kInt16);
    put_le(uint64_t(v), 2);
  } else if (v >= INT32_MIN && v <= INT32_MAX) {
    put(kInt32);
    put_le(uint64_t(v), 4);
  } else {
    put(kInt64);
    put_le(uint64_t(v), 8);
  }
}

void JsonWriter::real(double v) {
  before_value();
  if (format_ == Format::Text) return put_number_text(v);
  put(kReal64);
  put_le(packed_bits(v, Packing::Real64), 8);
}

void JsonWriter::numbers(const double* v, size_t n, Packing packing) { packed(v, n, packing); }
void JsonWriter::numbers(const int64_t* v, size_t n, Packing packing) { packed(v, n, packing); }

template <class T>
void JsonWriter::packed(const T* v, size_t n, Packing packing) {
  if (format_ == Format::Text) {
    begin_array();
    for (size_t i = 0; i < n; ++i) {
      before_value();
      if (packing == Packing::Real32)
        put_number_text(static_cast<float>(v[i]));
      else if (packing == Packing::Real64)
        put_number_text(static_cast<double>(v[i]));
      else
        put_number_text(static_cast<int64_t>(v[i]));
    }
    end_array();
    return;
  }
  before_value();
  put(kUniformArray);
  put(packing_tag(packing));
  put_length(n);
  const int width = int(number_width(packing_tag(packing)));
  for (size_t i = 0; i < n; ++i) put_le(packed_bits(v[i], packing), width);
}

template <class T>
void JsonWriter::put_number_text(T v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest form that reads back exactly
  out_.write(buf, r.ptr - buf);
}

void JsonWriter::put_le(uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) put(uint8_t(v >> (8 * i)));
}

void JsonWriter::put_length(uint64_t n) {
  if (n < 0xf1) {
    put(uint8_t(n));
  } else if (n <= 0xffff) {
    put(0xf2);
    put_le(n, 2);
  } else if (n <= 0xffffffffu) {
    put(0xf4);
    put_le(n, 4);
  } else {
    put(0xf8);
    put_le(n, 8);
  }
}

}  // namespace weft::io
