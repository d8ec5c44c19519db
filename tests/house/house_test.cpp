// The house rules that keep the code readable, checked on the sources: no file over 500 lines
// and no function over 80 lines in core/, engine/ and ui/, except where a comment says why
// ("house: long file because …" anywhere in the file, "house: long function because …" in the
// three lines above the function); core/ has no Qt; and every #include follows the arrows of
// docs/architecture.md (down or across, never up).
//
// Functions are found by a brace scanner, not a compiler: comments, strings and characters
// are blanked, then a `{` directly inside namespaces and classes whose head has a `)` opens a
// function body (lambdas and blocks inside it count as its lines). It finds what clang-tidy's
// readability-function-size finds on this tree.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace archet {
namespace {

constexpr int kMaxFileLines = 500;
constexpr int kMaxFunctionLines = 80;

struct LongFunction {
    int first_line = 0;
    int lines = 0;
    std::string head;
};

/// The source with comments, string and character literals replaced by spaces (newlines
/// kept, so line numbers stay).
std::string code_only(const std::string& text) {
    std::string out = text;
    enum { Code, Line, Block, String, Char } state = Code;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const char c = text[i], next = i + 1 < text.size() ? text[i + 1] : '\0';
        const bool newline = c == '\n';
        switch (state) {
            case Code:
                if (c == '/' && next == '/')
                    state = Line;
                else if (c == '/' && next == '*')
                    state = Block;
                else if (c == '"')
                    state = String;
                else if (c == '\'' &&
                         !(i > 0 && std::isxdigit(static_cast<unsigned char>(text[i - 1]))))
                    state = Char;  // a digit separator (1'000) is not a character literal
                else
                    continue;
                break;
            case Line:
                if (newline) state = Code;
                break;
            case Block:
                if (c == '*' && next == '/') out[i + 1] = ' ', ++i, state = Code;
                break;
            case String:
            case Char:
                if (c == '\\')
                    out[i] = ' ', ++i;
                else if (c == (state == String ? '"' : '\''))
                    state = Code;
                break;
        }
        if (i < out.size() && out[i] != '\n') out[i] = ' ';
    }
    return out;
}

std::vector<LongFunction> long_functions(const std::string& text) {
    const std::string code = code_only(text);
    static const std::regex scope_head(R"((^|[^\w])(namespace|class|struct|union|enum)([^\w]|$))");
    enum class Brace { Scope, Function, Other };
    std::vector<Brace> open;
    std::string head;  // the code since the last ; { or }
    int line = 1, function_start = 0;
    std::vector<LongFunction> found;
    for (const char c : code) {
        if (c == '\n') ++line;
        if (c == '{') {
            const bool at_scope_level =
                std::all_of(open.begin(), open.end(), [](Brace b) { return b == Brace::Scope; });
            Brace kind = Brace::Other;
            if (at_scope_level && std::regex_search(head, scope_head) &&
                head.find('(') == std::string::npos)
                kind = Brace::Scope;
            else if (at_scope_level && head.find(')') != std::string::npos)
                kind = Brace::Function, function_start = line;
            else if (at_scope_level)
                kind = Brace::Scope;  // extern "C", an initialiser: its own contents are checked
            open.push_back(kind);
            head.clear();
        } else if (c == '}') {
            if (!open.empty() && open.back() == Brace::Function &&
                line - function_start - 1 > kMaxFunctionLines)
                found.push_back({function_start, line - function_start - 1, ""});
            if (!open.empty()) open.pop_back();
            head.clear();
        } else if (c == ';') {
            head.clear();
        } else {
            head += c;
        }
    }
    return found;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

bool excused(const std::vector<std::string>& lines, int first_line) {
    for (int l = std::max(1, first_line - 3);
         l <= first_line && l <= static_cast<int>(lines.size()); ++l)
        if (lines[l - 1].find("house: long function because") != std::string::npos) return true;
    return false;
}

std::vector<std::filesystem::path> sources_in(const std::vector<std::string>& folders) {
    std::vector<std::filesystem::path> files;
    for (const auto& folder : folders)
        for (const auto& e :
             std::filesystem::recursive_directory_iterator(test::source_dir() / folder))
            if (e.path().extension() == ".cpp" || e.path().extension() == ".hpp")
                files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(House, TheScannerFindsLongFunctionsAndOnlyThose) {
    std::string body;
    for (int i = 0; i < kMaxFunctionLines + 1; ++i) body += "    x += 1;\n";
    const std::string source =
        "namespace a {\nstruct S { int f() const { return 1; } };\n"
        "// a } in a comment, \"{ in a string\", '{'\n"
        "int long_one(int x) {\n    auto l = [&] { return x; };\n" +
        body + "    return l();\n}\nint short_one() { return 2; }\n}\n";
    const auto found = long_functions(source);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].first_line, 4);
    EXPECT_EQ(found[0].lines, kMaxFunctionLines + 3);  // the lambda, the body, the return
    EXPECT_TRUE(long_functions("int f() {\n    return 1;\n}\n").empty());
}

TEST(House, NoFileOver500LinesAndNoFunctionOver80LinesInCoreEngineAndUi) {
    std::vector<std::string> problems;
    for (const auto& file : sources_in({"core", "engine", "ui"})) {
        const std::string text = test::read_file(file);
        const auto lines = lines_of(text);
        const auto name = std::filesystem::relative(file, test::source_dir()).string();
        if (static_cast<int>(lines.size()) > kMaxFileLines &&
            text.find("house: long file because") == std::string::npos)
            problems.push_back(name + " has " + std::to_string(lines.size()) + " lines");
        for (const auto& f : long_functions(text))
            if (!excused(lines, f.first_line))
                problems.push_back(name + ":" + std::to_string(f.first_line) + " a function of " +
                                   std::to_string(f.lines) + " lines");
    }
    std::string all;
    for (const auto& p : problems) all += "\n  " + p;
    EXPECT_TRUE(problems.empty()) << "split these into named parts, or say why in a comment:"
                                  << all;
}

/// The folder a source or header belongs to, as the arrows name it: core/PART, ui/link, or a
/// top-level folder.
std::string room_of(const std::filesystem::path& relative) {
    const auto first = *relative.begin();
    auto part = std::next(relative.begin());
    if (first == "core" && part != relative.end() && std::next(part) != relative.end()) {
        ++part;  // core/src/PART or core/include/archet/PART
        if (*part == "archet") ++part;
        return "core/" + part->string();
    }
    if (first == "ui" && part != relative.end() && *part == "link") return "ui/link";
    return first.string();
}

/// Every header a folder offers, by its include path ("archet/model/model.hpp"), to its room.
std::map<std::string, std::string> header_rooms() {
    std::map<std::string, std::string> rooms;
    for (const char* folder : {"core", "audio", "haptics", "engine", "ui"})
        for (const auto& e :
             std::filesystem::recursive_directory_iterator(test::source_dir() / folder)) {
            const auto relative = std::filesystem::relative(e.path(), test::source_dir());
            const std::string path = relative.string();
            const auto at = path.find("/include/");
            if (e.path().extension() == ".hpp" && at != std::string::npos)
                rooms[path.substr(at + 9)] = room_of(relative);
        }
    return rooms;
}

TEST(House, EveryIncludeFollowsTheArrows) {
    // What each room may use besides itself: docs/architecture.md's diagram, as data.
    const std::map<std::string, std::set<std::string>> may_use{
        {"core/common", {}},
        {"core/model", {"core/common"}},
        {"core/files", {"core/model", "core/common"}},
        {"core/physics", {"core/model", "core/common"}},
        {"core/analysis", {"core/physics", "core/model", "core/common"}},
        {"core/builders", {"core/analysis", "core/physics", "core/model", "core/common"}},
        {"core/ipc", {"core/model", "core/common"}},
        {"core/midi", {"core/analysis", "core/files", "core/model", "core/common"}},
    };
    const std::set<std::string> core{"core/common",   "core/model",    "core/files", "core/physics",
                                     "core/analysis", "core/builders", "core/ipc",   "core/midi"};
    auto allowed = [&](const std::string& room, const std::string& used) {
        if (room == used) return true;
        if (auto it = may_use.find(room); it != may_use.end()) return it->second.count(used) > 0;
        const bool in_core = core.count(used) > 0;
        if (room == "audio" || room == "haptics" || room == "ui/link") return in_core;
        if (room == "engine") return in_core || used == "audio" || used == "haptics";
        if (room == "ui")
            return in_core || used == "audio" || used == "haptics" || used == "ui/link";
        return false;
    };
    const auto rooms = header_rooms();
    const std::regex include(R"re(#include\s+"(archet/[^"]+)")re");
    std::vector<std::string> problems;
    for (const auto& file : sources_in({"core", "audio", "haptics", "engine", "ui"})) {
        const auto relative = std::filesystem::relative(file, test::source_dir());
        const std::string room = room_of(relative), text = test::read_file(file);
        for (std::sregex_iterator m(text.begin(), text.end(), include), end; m != end; ++m) {
            const auto it = rooms.find((*m)[1]);
            if (it == rooms.end())
                problems.push_back(relative.string() + " includes " + (*m)[1].str() +
                                   ", which no folder offers");
            else if (!allowed(room, it->second))
                problems.push_back(relative.string() + " (" + room + ") uses " + it->second);
        }
    }
    std::string all;
    for (const auto& p : problems) all += "\n  " + p;
    EXPECT_TRUE(problems.empty()) << "an arrow points up:" << all;
}

TEST(House, CoreHasNoQt) {
    const std::regex qt(R"(#include\s*<Q[A-Za-z]*>|#include\s*<Qt)");
    for (const auto& file : sources_in({"core"}))
        EXPECT_FALSE(std::regex_search(test::read_file(file), qt)) << file;
}

}  // namespace
}  // namespace archet
