#include "config/json_reader.h"

#include "config/nearest_name.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "config/text_util.h"
#include "foundation/errors.h"

namespace sl {

namespace {

// "line L, column C" (1-based) of the 1-based byte position `byte` in `text`.
std::string line_column(const std::string& text, size_t byte) {
    size_t at = std::min(byte == 0 ? 0 : byte - 1, text.size());  // 0-based offending char
    size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
    size_t newline = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
    size_t line_start = newline == std::string::npos ? 0 : newline + 1;
    return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
}

// nlohmann's message after its own "[json.exception...] parse error at line L, column C: ".
std::string parse_error_detail(const std::string& what) {
    size_t p = what.find(", column ");
    p = (p == std::string::npos) ? std::string::npos : what.find(": ", p);
    std::string detail = (p == std::string::npos) ? what : what.substr(p + 2);
    const std::string redundant = "syntax error ";
    if (detail.rfind(redundant, 0) == 0) detail.erase(0, redundant.size());
    return detail;
}

// A SAX handler that builds the document like nlohmann's own DOM parser and refuses what
// nlohmann allows but a scene must not have: duplicate keys (it keeps the last silently) and
// deep nesting (which overflows the stack when the value is destroyed). It tracks the path it
// is at so that the message can name the key.
//
// Not nlohmann's parser callback: after every nested object or array it scans the whole
// parent for values the callback discarded, which made parsing quadratic in an object's key
// count (80,000 materials took 45 s). Here every event costs O(log keys).
class StrictDomParser {
public:
    StrictDomParser(Json& root, const std::string& source) : dom_(root), source_(&source) {}

    bool null() { return value(dom_.null()); }
    bool boolean(bool v) { return value(dom_.boolean(v)); }
    bool number_integer(Json::number_integer_t v) { return value(dom_.number_integer(v)); }
    bool number_unsigned(Json::number_unsigned_t v) { return value(dom_.number_unsigned(v)); }
    bool number_float(Json::number_float_t v, const Json::string_t& s) { return value(dom_.number_float(v, s)); }
    bool string(Json::string_t& v) { return value(dom_.string(v)); }
    bool binary(Json::binary_t& v) { return value(dom_.binary(v)); }
    bool start_object(std::size_t n) {
        open(false);
        return dom_.start_object(n);
    }
    bool start_array(std::size_t n) {
        open(true);
        return dom_.start_array(n);
    }
    bool key(Json::string_t& k) {
        Frame& f = frames_.back();
        f.key = k;
        if (!f.keys.insert(k).second) throw_key_error(*source_, path(), "duplicate key");
        return dom_.key(k);
    }
    bool end_object() { return close(dom_.end_object()); }
    bool end_array() { return close(dom_.end_array()); }
    template <class Exception>
    bool parse_error(std::size_t at, const std::string& token, const Exception& e) {
        return dom_.parse_error(at, token, e);  // throws e
    }

private:
    static constexpr size_t kMaxDepth = 64;  // scenes need about 4

    struct Frame {
        bool array = false;
        size_t index = 0;   // arrays: the element being read
        std::string key{};  // objects: the key being read
        std::set<std::string> keys{};
    };

    void open(bool array) {
        if (frames_.size() >= kMaxDepth)
            throw_key_error(*source_, path(),
                            "JSON nested more than " + std::to_string(kMaxDepth) + " levels deep");
        frames_.push_back({array});
    }
    bool close(bool ok) {
        frames_.pop_back();
        return value(ok);
    }
    bool value(bool ok) {  // an element is complete
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        return ok;
    }
    std::string path() const {
        std::string p;
        for (const Frame& f : frames_)
            p = f.array ? element_path(p, f.index) : (p.empty() ? f.key : p + "." + f.key);
        return p;
    }

    nlohmann::detail::json_sax_dom_parser<Json> dom_;
    const std::string* source_;
    std::vector<Frame> frames_;
};

std::optional<int64_t> as_int64(const Json& v) {
    if (v.is_number_unsigned()) {
        uint64_t u = v.get<uint64_t>();
        if (u > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) return std::nullopt;
        return static_cast<int64_t>(u);
    }
    if (v.is_number_integer()) return v.get<int64_t>();
    if (v.is_number_float()) {  // 1e5 is a float in JSON but a fine integer
        double d = v.get<double>();
        if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9e18)
            return static_cast<int64_t>(d);
    }
    return std::nullopt;
}

std::string describe_triple_shape(const Range& r) {
    return r.lo == Range::any().lo && r.hi == Range::any().hi
               ? "an array of 3 finite numbers"
               : "an array of 3 numbers, each " + r.describe();
}

}  // namespace

Json parse_json_text(const std::string& text, const std::string& source) {
    // nlohmann takes a NUL byte for the end of the input: text after it would be ignored
    // unread, and one in the middle gives "unexpected end of input".
    if (size_t nul = text.find('\0'); nul != std::string::npos)
        throw InputError(printable(source) + ": " + line_column(text, nul + 1) +
                         ": a NUL byte: a scene file is JSON text");
    try {
        Json root;
        StrictDomParser sax(root, source);
        Json::sax_parse(text, &sax);
        return root;
    } catch (const Json::parse_error& e) {
        throw InputError(printable(source) + ": " + line_column(text, e.byte) +
                         ": JSON syntax error: " + printable(parse_error_detail(e.what()), 200));
    } catch (const Json::out_of_range& e) {
        // A number too large for a double (1e999). nlohmann gives no position, but it quotes
        // the number: find its first occurrence to name the line.
        std::string what = e.what();
        size_t a = what.find('\''), b = what.rfind('\'');
        std::string number = (a != std::string::npos && b > a) ? what.substr(a + 1, b - a - 1) : "";
        size_t at = number.empty() ? std::string::npos : text.find(number);
        std::string where = at == std::string::npos ? "" : line_column(text, at + 1) + ": ";
        throw InputError(printable(source) + ": " + where + "number out of range: " +
                         printable(number) + " (must be a finite number)");
    }
}

bool Range::contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lo_open ? !(v > lo) : !(v >= lo)) return false;
    return hi_open ? v < hi : v <= hi;
}

std::string Range::describe() const {
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    std::string s = "a finite number";
    if (has_lo && has_hi)
        s += std::string(" in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " +
             format_number(hi) + (hi_open ? ")" : "]");
    else if (has_lo)
        s += (lo_open ? " > " : " >= ") + format_number(lo);
    else if (has_hi)
        s += (hi_open ? " < " : " <= ") + format_number(hi);
    return s;
}

void throw_key_error(const std::string& source, const std::string& path, const std::string& what) {
    std::string where = path.empty() ? "top level" : "key '" + printable(path, 200) + "'";
    throw InputError(printable(source) + ": " + where + ": " + printable(what, 400));
}

std::string describe_json(const Json& v) {
    return printable(v.dump(-1, ' ', false, Json::error_handler_t::replace), 60);
}

std::string element_path(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

JsonObject::JsonObject(const Json& value, std::string path, const std::string& source)
    : value_(value), path_(std::move(path)), source_(source) {
    if (!value_.is_object()) fail_here("must be a JSON object {...}, got " + describe_json(value_));
}

void JsonObject::expect_keys(std::span<const std::string_view> allowed) const {
    for (const auto& item : value_.items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
        std::string list;
        for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
        const std::string guess = nearest_name(item.key(), allowed);
        fail(item.key(), "unknown key" + (guess.empty() ? std::string() : ": did you mean '" + guess + "'?") +
                             " (expected one of: " + list + ")");
    }
}

bool JsonObject::has(std::string_view key) const {
    return value_.find(std::string(key)) != value_.end();
}

const Json& JsonObject::at(std::string_view key) const {
    auto it = value_.find(std::string(key));
    if (it == value_.end()) fail(key, "required key is missing");
    return *it;
}

std::string JsonObject::path_of(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void JsonObject::fail(std::string_view key, const std::string& what) const {
    throw_key_error(source_, path_of(key), what);
}

void JsonObject::fail_here(const std::string& what) const {
    throw_key_error(source_, path_, what);
}

double JsonObject::number(std::string_view key, Range r) const {
    const Json& v = at(key);
    if (!v.is_number() || !r.contains(v.get<double>()))
        fail(key, "must be " + r.describe() + ", got " + describe_json(v));
    return v.get<double>();
}

double JsonObject::number(std::string_view key, Range r, double dflt) const {
    return has(key) ? number(key, r) : dflt;
}

int64_t JsonObject::integer(std::string_view key, int64_t lo, int64_t hi) const {
    const Json& v = at(key);
    std::optional<int64_t> i = as_int64(v);
    if (!i || *i < lo || *i > hi)
        fail(key, "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                      ", got " + describe_json(v));
    return *i;
}

int64_t JsonObject::integer(std::string_view key, int64_t lo, int64_t hi, int64_t dflt) const {
    return has(key) ? integer(key, lo, hi) : dflt;
}

uint64_t JsonObject::unsigned_integer(std::string_view key, uint64_t dflt) const {
    if (!has(key)) return dflt;
    const Json& v = at(key);
    if (v.is_number_unsigned()) return v.get<uint64_t>();
    std::optional<int64_t> i = as_int64(v);
    if (!i || *i < 0)
        fail(key, "must be an integer in 0.." +
                      std::to_string(std::numeric_limits<uint64_t>::max()) + ", got " +
                      describe_json(v));
    return static_cast<uint64_t>(*i);
}

bool JsonObject::boolean(std::string_view key, bool dflt) const {
    if (!has(key)) return dflt;
    const Json& v = at(key);
    if (!v.is_boolean()) fail(key, "must be true or false, got " + describe_json(v));
    return v.get<bool>();
}

std::string JsonObject::string(std::string_view key) const {
    const Json& v = at(key);
    if (!v.is_string()) fail(key, "must be a string, got " + describe_json(v));
    return v.get<std::string>();
}

int JsonObject::choice(std::string_view key,
                       std::initializer_list<std::string_view> choices) const {
    const Json& v = at(key);
    if (v.is_string()) {
        auto it = std::find(choices.begin(), choices.end(), v.get<std::string>());
        if (it != choices.end()) return static_cast<int>(it - choices.begin());
    }
    std::string list;
    for (std::string_view c : choices)
        list += (list.empty() ? "\"" : ", \"") + std::string(c) + "\"";
    const std::string guess = v.is_string() ? nearest_name(v.get<std::string>(), choices) : std::string();
    fail(key, "must be one of " + list + ", got " + describe_json(v) +
                  (guess.empty() ? std::string() : " (did you mean \"" + guess + "\"?)"));
}

int JsonObject::choice(std::string_view key, std::initializer_list<std::string_view> choices,
                       int dflt) const {
    return has(key) ? choice(key, choices) : dflt;
}

Triple JsonObject::triple(std::string_view key, Range r) const {
    const Json& v = at(key);
    bool ok = v.is_array() && v.size() == 3;
    for (size_t i = 0; ok && i < 3; ++i) ok = v[i].is_number() && r.contains(v[i].get<double>());
    if (!ok) fail(key, "must be " + describe_triple_shape(r) + ", got " + describe_json(v));
    return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

Triple JsonObject::triple(std::string_view key, Range r, Triple dflt) const {
    return has(key) ? triple(key, r) : dflt;
}

Triple JsonObject::number_or_triple(std::string_view key, Range r, Triple dflt) const {
    if (!has(key)) return dflt;
    const Json& v = at(key);
    if (v.is_array()) return triple(key, r);
    if (!v.is_number() || !r.contains(v.get<double>()))
        fail(key, "must be " + r.describe() + " or " + describe_triple_shape(r) + ", got " +
                      describe_json(v));
    double d = v.get<double>();
    return {d, d, d};
}

JsonObject JsonObject::object(std::string_view key) const {
    return JsonObject(at(key), path_of(key), source_);
}

}  // namespace sl
