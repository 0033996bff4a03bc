#pragma once
// Strict reading of JSON objects for the scene parser: every key is known, every value is
// type- and range-checked, and every failure is one InputError line naming the source file and
// the dotted key path: `<source>: key 'shapes[2].radius': must be a finite number > 0, got -1`.
#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

namespace sl {

using Json = nlohmann::json;

// Parses JSON text. Syntax errors name the line and column; duplicate keys are errors too.
Json parse_json_text(const std::string& text, const std::string& source);

// A closed or open interval of accepted numbers; describe() words it for messages.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = true, hi_open = true;

    bool contains(double v) const;
    std::string describe() const;  // "a finite number > 0", "a finite number in [0, 1]", ...

    static Range any() { return {}; }
    static Range positive() { return {0, std::numeric_limits<double>::infinity(), true, true}; }
    static Range non_negative() {
        return {0, std::numeric_limits<double>::infinity(), false, true};
    }
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
};

using Triple = std::array<double, 3>;

// A JSON value that must be an object, at a key path inside a source file.
class JsonObject {
public:
    JsonObject(const Json& value, std::string path, const std::string& source);

    // Every key present must be one of `allowed` (the parser's lists: config/scene_keys.h).
    void expect_keys(std::span<const std::string_view> allowed) const;

    bool has(std::string_view key) const;
    const Json& at(std::string_view key) const;  // required: fails when missing
    std::string path_of(std::string_view key) const;
    const std::string& path() const { return path_; }
    const std::string& source() const { return source_; }
    const Json& json() const { return value_; }

    [[noreturn]] void fail(std::string_view key, const std::string& what) const;
    [[noreturn]] void fail_here(const std::string& what) const;

    // Typed getters. Without a default the key is required.
    double number(std::string_view key, Range r) const;
    double number(std::string_view key, Range r, double dflt) const;
    int64_t integer(std::string_view key, int64_t lo, int64_t hi) const;
    int64_t integer(std::string_view key, int64_t lo, int64_t hi, int64_t dflt) const;
    uint64_t unsigned_integer(std::string_view key, uint64_t dflt) const;
    bool boolean(std::string_view key, bool dflt) const;
    std::string string(std::string_view key) const;
    // One of `choices`; returns its index.
    int choice(std::string_view key, std::initializer_list<std::string_view> choices) const;
    int choice(std::string_view key, std::initializer_list<std::string_view> choices,
               int dflt) const;
    Triple triple(std::string_view key, Range r) const;
    Triple triple(std::string_view key, Range r, Triple dflt) const;
    // A number (used for all three components) or an array of 3 numbers.
    Triple number_or_triple(std::string_view key, Range r, Triple dflt) const;
    JsonObject object(std::string_view key) const;  // required

private:
    const Json& value_;
    std::string path_;
    const std::string& source_;
};

// Throws InputError "<source>: key '<path>': <what>".
[[noreturn]] void throw_key_error(const std::string& source, const std::string& path,
                                  const std::string& what);

// A short one-line rendering of a JSON value for messages.
std::string describe_json(const Json& v);

// "<path>[<i>]": the key path of an array element.
std::string element_path(const std::string& path, size_t i);

}  // namespace sl
