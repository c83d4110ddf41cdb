#include "core/io/Json.hpp"


#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/io/Memory.hpp"
#include "core/io/Sha256.hpp"

namespace archipelago::io {

using nlohmann::json;

namespace {
/// The byte (1-based) where the nesting of arrays and objects outside strings first exceeds `limit`, or 0.
/// Linear; checks nothing else of the syntax.
std::size_t firstByteDeeperThan(std::string_view text, int limit) {
  int depth = 0;
  bool inString = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i + 1;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return 0;
}
/// A SAX handler that finds the first key repeated within one object (nlohmann would keep the last silently).
struct RepeatedKeyFinder : nlohmann::json_sax<json> {
  std::vector<std::set<std::string>> keysOfOpenObjects;
  std::string repeated;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    keysOfOpenObjects.emplace_back();
    return true;
  }
  bool key(string_t& k) override {
    if (!keysOfOpenObjects.back().insert(k).second) {
      repeated = k;
      return false;  // stops the pass
    }
    return true;
  }
  bool end_object() override {
    keysOfOpenObjects.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    throw e;  // rethrown as the json::exception it is (a parse_error or an out_of_range)
  }
};

}  // namespace

json parseJson(std::string_view text) {
  // The depth first, on the text: nothing deep is ever built, parsed or printed.
  if (const std::size_t at = firstByteDeeperThan(text, kMaxJsonDepth); at != 0)
    throw BadFile("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                                std::to_string(at) + "); no Archipelago file is");
  // Repeated keys by a SAX pass, then the document by nlohmann's plain parser: both linear.  (nlohmann's parser
  // with a callback scans the enclosing array at the end of every object: quadratic, 34 s for 200,000 "{}".)
  RepeatedKeyFinder finder;
  try {
    (void)json::sax_parse(text.begin(), text.end(), &finder);
    if (!finder.repeated.empty())
      throw BadFile("the key '" + shortText(finder.repeated) + "' appears twice in one object");
    return json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    // Every error of nlohmann's parser, not only parse_error: a number too large for a double
    // ("215e4434690031883725") is an out_of_range (406), found by fuzz_runfile and fuzz_runspec.
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line 1, column 2: …"
    std::string what = e.what();
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    throw BadFile("not valid JSON: " + shortText(what, 200));
  }
}

std::string jsonChecksum(const json& content) { return "sha256:" + sha256Hex(content.dump(1)); }

std::string describeJson(const json& v) {
  switch (v.type()) {
    case json::value_t::array:
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " entry" : " entries");
    case json::value_t::object:
      return "an object of " + std::to_string(v.size()) + (v.size() == 1 ? " key" : " keys");
    case json::value_t::string: {
      const std::string& text = v.get_ref<const std::string&>();
      return text.size() <= 40 ? json(text).dump() : json(shortText(text, 40)).dump();
    }
    default:
      return v.dump();  // a number, a bool, null: short and flat
  }
}

json loadJsonFile(const std::filesystem::path& path, std::uintmax_t maxBytes) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) {
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size <= maxBytes) checkParseMemory(size, path.string());
  }
  return parseJson(readRegularFile(path, maxBytes));  // readRegularFile says what is wrong with a path
}

void checkParseMemory(std::uintmax_t textBytes, const std::string& what) {
  // Below 16 MiB of text the check costs more than it can save.
  if (textBytes < (std::uintmax_t{16} << 20)) return;
  const std::uintmax_t limit = std::numeric_limits<std::uintmax_t>::max() / (kJsonBytesPerTextByte + 1);
  checkMemory(textBytes > limit ? std::numeric_limits<std::uintmax_t>::max() : textBytes * (kJsonBytesPerTextByte + 1),
              "reading " + what + " (" + std::to_string(textBytes >> 20) + " MiB of JSON)");
}

std::optional<std::uint64_t> wholeJson(const nlohmann::json& value, std::uint64_t max) noexcept {
  std::uint64_t n = 0;
  if (value.is_number_unsigned()) n = value.get<std::uint64_t>();
  else if (value.is_number_integer() && value.get<std::int64_t>() >= 0) n = static_cast<std::uint64_t>(value.get<std::int64_t>());
  else return std::nullopt;
  if (n > max) return std::nullopt;
  return n;
}

// --- JsonField -------------------------------------------------------------------------------------------------

JsonField::JsonField(const json& document, std::string_view name, std::string_view prefix)
    : value_(&document), document_(name), prefix_(prefix) {}

JsonField::JsonField(const json& value, std::string path, const JsonField& parent)
    : value_(&value), path_(std::move(path)), document_(parent.document_), prefix_(parent.prefix_) {}

std::string JsonField::name() const { return path_.empty() ? std::string(document_) : path_; }

void JsonField::refuseDocument(std::string_view what) const {
  throw BadFile(std::string(prefix_) + std::string(what));
}
void JsonField::refuse(std::string_view what) const { refuseDocument(name() + " " + std::string(what)); }
void JsonField::refuseValue(std::string_view rule) const {
  refuseDocument(name() + " = " + describeJson(*value_) + " " + std::string(rule));
}

const JsonField& JsonField::object() const {
  if (!value_->is_object()) refuse("must be a JSON object, not " + describeJson(*value_));
  return *this;
}

bool JsonField::contains(std::string_view key) const { return value_->is_object() && value_->contains(key); }

std::optional<JsonField> JsonField::find(std::string_view key) const {
  const auto it = object().value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonField(*it, path_.empty() ? std::string(key) : path_ + "." + std::string(key), *this);
}

JsonField JsonField::operator[](std::string_view key) const {
  std::optional<JsonField> member = find(key);
  if (!member) refuse("has no '" + std::string(key) + "'");
  return std::move(*member);
}

JsonField JsonField::operator[](std::size_t i) const {
  if (!value_->is_array() || i >= value_->size()) refuse("has no entry " + std::to_string(i));
  return JsonField((*value_)[i], name() + "[" + std::to_string(i) + "]", *this);
}

const JsonField& JsonField::keys(std::initializer_list<std::string_view> required,
                                 std::initializer_list<std::string_view> optional) const {
  object();
  const auto known = [&](const std::string& k) {
    for (const auto& list : {required, optional})
      for (std::string_view r : list)
        if (r == k) return true;
    return false;
  };
  for (auto it = value_->begin(); it != value_->end(); ++it)
    if (!known(it.key())) refuseDocument("unknown key '" + shortText(it.key()) + "' in " + name());
  for (std::string_view k : required)
    if (!value_->contains(k)) refuse("has no '" + std::string(k) + "'");
  return *this;
}

std::size_t JsonField::array(std::size_t maxEntries) const {
  if (!value_->is_array()) refuse("must be an array, not " + describeJson(*value_));
  if (value_->size() > maxEntries)
    refuse("has " + std::to_string(value_->size()) + " entries; at most " + std::to_string(maxEntries));
  return value_->size();
}

void JsonField::tuple(std::size_t entries, std::string_view shape) const {
  if (!value_->is_array() || value_->size() != entries)
    refuse("must be " + std::string(shape) + ", not " + describeJson(*value_));
}

std::uint64_t JsonField::whole(std::uint64_t max, std::uint64_t min) const {
  const std::optional<std::uint64_t> n = wholeJson(*value_, max);
  if (!n || *n < min)
    refuseValue("must be a whole number in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return *n;
}

std::uint64_t JsonField::wholeOrExactReal(std::uint64_t max) const {
  if (!value_->is_number()) refuse("must be a number, not " + describeJson(*value_));
  std::optional<std::uint64_t> n = wholeJson(*value_, max);
  if (value_->is_number_float()) {
    const double d = value_->get<double>();
    // 2^64 is the first double past the range of std::uint64_t.
    if (d >= 0 && d < 18446744073709551616.0 && std::floor(d) == d && static_cast<std::uint64_t>(d) <= max)
      n = static_cast<std::uint64_t>(d);
  }
  if (!n) refuseValue("must be a whole number in [0, " + std::to_string(max) + "]");
  return *n;
}

std::int64_t JsonField::integer(std::int64_t min, std::int64_t max) const {
  const json& v = *value_;
  if (!v.is_number_integer() || (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) ||
      v.get<std::int64_t>() < min || v.get<std::int64_t>() > max)
    refuseValue("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return v.get<std::int64_t>();
}

double JsonField::real() const {
  if (!value_->is_number()) refuse("must be a number, not " + describeJson(*value_));
  const double d = value_->get<double>();
  if (!std::isfinite(d)) refuse("must be finite");
  return d;
}

double JsonField::nonNegative() const {
  const double d = real();
  if (!(d >= 0)) refuseValue("must be ≥ 0");
  return d;
}

double JsonField::realOr(double null) const { return isNull() ? null : real(); }

bool JsonField::boolean() const {
  if (!value_->is_boolean()) refuse("must be true or false, not " + describeJson(*value_));
  return value_->get<bool>();
}

std::string JsonField::string(std::size_t maxBytes) const {
  if (!value_->is_string()) refuse("must be a string, not " + describeJson(*value_));
  const std::string& s = value_->get_ref<const std::string&>();
  if (s.size() > maxBytes) refuse("is longer than " + std::to_string(maxBytes) + " bytes");
  return s;
}

void checkSignature(nlohmann::json& j, const JsonField& root, std::uint64_t version, std::string_view noun,
                    std::string_view subject, const std::function<void(const std::string&)>& refuse) {
  const auto breach = [&](const std::string& why) {
    refuse(why);
    throw BadFile(why);
  };
  if (const auto given = root.find("format_version")) {
    (void)given->whole(version, version);
    if (!root.contains("checksum") || !root["checksum"].value().is_string())
      breach("checksum: a signed " + std::string(noun) + " (version " + std::to_string(version) + ") must have one");
    const std::string sum = root["checksum"].string();
    j.erase("checksum");
    if (jsonChecksum(j) != sum)
      breach(std::string(subject) + " was modified after it was written (its checksum does not match its content)");
  } else if (root.contains("checksum")) {
    breach("checksum without format_version");
  }
}

}  // namespace archipelago::io
