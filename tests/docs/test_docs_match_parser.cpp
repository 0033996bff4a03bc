// docs/scene-format.md lists exactly the keys the scene parser accepts, object by object.
//
// The doc's convention: every key has a row in a key table (a table whose first column is
// headed `key`; the row's first cell holds the key, or several, as `key`) under the heading of
// its object: `## camera`, and for an object with a `type` `### TYPE` inside its section
// (`### quad` under `## shapes`). The top level's table is under `## The whole file`; a key
// `a.b` in object O's table is the key b of the object "O.a" (`bounds.min` under `## medium`).
// The parser's side is config/scene_keys.h, the lists parse_scene.cpp checks every object with.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <utility>

#include "config/parse_scene.h"
#include "config/scene_keys.h"
#include "foundation/errors.h"
#include "tests/docs/doc_text.h"

namespace sl {
namespace {

using ObjectId = std::pair<std::string, std::string>;  // (object, type)
using KeySets = std::map<ObjectId, std::set<std::string>>;

std::string name_of(const ObjectId& id) {
    std::string o = id.first.empty() ? "the top level" : "'" + id.first + "'";
    return id.second.empty() ? o : o + " of type '" + id.second + "'";
}

KeySets keys_in_doc(const std::string& text) {
    KeySets doc;
    std::string h2, h3;
    bool in_code = false, in_key_table = false, past_header = false;
    for (const std::string& raw : test::lines_of(text)) {
        const std::string line = test::trim(raw);
        if (line.rfind("```", 0) == 0) { in_code = !in_code; continue; }
        if (in_code) continue;
        if (line.rfind("## ", 0) == 0) { h2 = test::trim(line.substr(3)); h3.clear(); }
        if (line.rfind("### ", 0) == 0) h3 = test::trim(line.substr(4));
        if (!test::is_table_row(line)) { in_key_table = past_header = false; continue; }
        const std::vector<std::string> cells = test::table_cells(line);
        if (!in_key_table && !past_header) {  // a table's header row
            in_key_table = !cells.empty() && cells[0] == "key";
            past_header = true;
            continue;
        }
        if (!in_key_table || test::is_separator_row(line)) continue;
        const std::string object = h2 == "The whole file" ? "" : h2;
        for (const std::string& key : test::backticked(cells[0])) {
            const size_t dot = key.find('.');
            if (dot == std::string::npos)
                doc[{object, h3}].insert(key);
            else  // a key of a nested object: medium's bounds.min is medium.bounds' min
                doc[{object + "." + key.substr(0, dot), ""}].insert(key.substr(dot + 1));
        }
    }
    return doc;
}

KeySets keys_of_parser() {
    KeySets parser;
    for (const SceneObjectKeys& o : scene_object_keys()) {
        std::set<std::string>& keys = parser[{std::string(o.object), std::string(o.type)}];
        for (std::string_view k : o.keys) keys.insert(std::string(k));
    }
    return parser;
}

const std::string kDoc = "docs/scene-format.md";

TEST(DocsMatchParser, SceneFormatListsEveryKeyTheParserAcceptsAndNoOther) {
    const std::string text = test::read_text(test::source_path(kDoc));
    ASSERT_FALSE(text.empty()) << kDoc << " could not be read";
    const KeySets doc = keys_in_doc(text), parser = keys_of_parser();
    for (const auto& [id, keys] : parser) {
        auto it = doc.find(id);
        if (it == doc.end()) {
            ADD_FAILURE() << kDoc << ": no key table for " << name_of(id)
                          << ", which the parser reads (give it a section with a `key` table)";
            continue;
        }
        for (const std::string& k : keys)
            EXPECT_TRUE(it->second.count(k))
                << kDoc << ": key '" << k << "' of " << name_of(id) << " is accepted by the parser but not documented";
        for (const std::string& k : it->second)
            EXPECT_TRUE(keys.count(k))
                << kDoc << ": key '" << k << "' of " << name_of(id) << " is documented but the parser refuses it";
    }
    for (const auto& [id, keys] : doc)
        EXPECT_TRUE(parser.count(id)) << kDoc << ": a key table for " << name_of(id)
                                      << ", an object (or type) the parser does not read";
}

// The lists are the parser's own: an unknown key in each object is refused with that very list.
std::string scene_with(const ObjectId& id) {
    std::string camera = R"("camera": {"position": [0, 0, 3], "look_at": [0, 0, 0])";
    std::string materials = R"("materials": {"m": {"type": "diffuse"}})";
    std::string light = R"({"type": "point", "position": [0, 1, 0], "power": [1, 1, 1]})";
    std::string lights = R"("lights": [)" + light + "]";
    std::string extra;
    const std::string bogus = R"("zzz_not_a_key": 1)";
    const std::string& o = id.first;
    const std::string type = R"("type": ")" + id.second + R"(", )";
    if (o.empty()) extra = bogus;
    else if (o == "camera") camera.insert(camera.size(), ", " + bogus);
    else if (o == "materials") materials = R"("materials": {"m": {)" + type + bogus + "}}";
    else if (o == "shapes") extra = R"("shapes": [{)" + type + bogus + "}]";
    else if (o == "lights") lights = R"("lights": [{)" + type + bogus + "}, " + light + "]";
    else if (o == "medium.bounds") extra = R"("medium": {"bounds": {)" + bogus + "}}";
    else extra = "\"" + o + "\": {" + bogus + "}";
    return "{" + camera + "}, " + materials + ", " + lights + (extra.empty() ? "" : ", " + extra) + "}";
}

TEST(DocsMatchParser, TheParserRefusesAnUnknownKeyWithTheListedKeys) {
    for (const SceneObjectKeys& o : scene_object_keys()) {
        const ObjectId id{std::string(o.object), std::string(o.type)};
        std::string expected;
        for (std::string_view k : o.keys) expected += (expected.empty() ? "" : ", ") + std::string(k);
        const std::string json = scene_with(id);
        try {
            parse_scene_text(json, "keys.json", ".");
            ADD_FAILURE() << name_of(id) << ": a bogus key was accepted in " << json;
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("zzz_not_a_key"), std::string::npos) << name_of(id) << ": " << what;
            EXPECT_NE(what.find("(expected one of: " + expected + ")"), std::string::npos)
                << name_of(id) << ": the parser's message does not list config/scene_keys.h's keys: " << what;
        }
    }
}

}  // namespace
}  // namespace sl
