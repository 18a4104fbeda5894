// The one mangling of names in generated code (cpp_identifier): plain names unchanged, every
// other name escaped, injective, never a reserved identifier, never a name of the generated code
// nor a macro of the headers it and the simulation program include.
#include "eomgen/codegen/cpp_identifier.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "eomgen/codegen/emit_model.hpp"
#include "eomgen_build_config.hpp"  // how eomgen simulate compiles (build/generator/cli/)
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

namespace fs = std::filesystem;

bool is_unreserved_identifier(const std::string& id) {
  static const std::regex identifier("[A-Za-z][A-Za-z0-9_]*");
  return std::regex_match(id, identifier) && id.find("__") == std::string::npos;
}

TEST(CppIdentifier, PlainNamesStayAsTheyAre) {
  for (const char* name : {"m", "l1", "theta_dot", "q1", "x_y", "J_b1", "IRxx", "wheelbase", "q_0", "x_1_y", "v_0_x",
                           "M_11_PI", "v_0", "x_22Dy", "w0", "k1", "eomgen_models"})
    EXPECT_EQ(cpp_identifier(name), name);
  // the generated headers of generated/ keep their fields
  for (const fs::directory_entry& file : fs::directory_iterator(testing::source_dir() / "models")) {
    if (!file.is_regular_file() || file.path().extension() != ".eom") continue;  // models/robots/ holds URDF
    const Model model = load_model(file.path().string());
    for (const Parameter& p : model.system.variables().parameters())
      EXPECT_EQ(cpp_identifier(p.name), p.name) << file.path();
    EXPECT_EQ(cpp_identifier(model.name), model.name);
  }
}

TEST(CppIdentifier, NamesOfIssue16GetIdentifiersOfTheirOwn) {
  const std::map<std::string, std::string> expected = {
      {"x__y", "x_1_y_"}, {"x_y", "x_y"},         {"_x", "v_0_x_"},       {"v_x", "v_x"},
      {"x_", "x_1_"},     {"x__", "x_1_1_"},      {"fields", "fields_"},  {"np", "np_"},
      {"EOF", "EOF_"},    {"NULL", "NULL_"},      {"INFINITY", "INFINITY_"}, {"NAN", "NAN_"},
      {"M_PI", "M_PI_"},  {"INT_MAX", "INT_MAX_"}, {"SIZE_MAX", "SIZE_MAX_"}, {"EDOM", "EDOM_"},
      {"RAND_MAX", "RAND_MAX_"}, {"linux", "linux_"}, {"unix", "unix_"}, {"i386", "i386_"},
      {"errno", "errno_"}, {"assert", "assert_"}, {"stdin", "stdin_"}, {"stdout", "stdout_"},
      {"int", "int_"},    {"class", "class_"},    {"Scalar", "Scalar_"},  {"q", "q_"},
      {"c", "c_"},        {"T", "T_"},            {"sin", "sin_"},        {"M_1_PI", "M_11_PI_"},
      {"_hidden", "v_0_hidden_"}, {"__x", "v_0_1_x_"}, {"my-model", "my_22Dmodel_"}, {"2link", "v_02link_"},
      {"", "v_0_"}};
  for (const auto& [name, id] : expected) EXPECT_EQ(cpp_identifier(name), id) << "'" << name << "'";
}

// every string of up to `length` characters of `alphabet`
std::vector<std::string> all_strings(const std::string& alphabet, std::size_t length) {
  std::vector<std::string> out{""};
  for (std::size_t begin = 0, n = 0; n < length; ++n) {
    const std::size_t end = out.size();
    for (std::size_t i = begin; i < end; ++i)
      for (char c : alphabet) out.push_back(out[i] + c);
    begin = end;
  }
  return out;
}

TEST(CppIdentifier, IsInjectiveAndNeverReservedOnAdversarialNames) {
  // the escape's own characters ('_', '0', '1', '2', 'v', hex digits), a letter, a byte that is
  // no identifier's: every collision of an escape with a plain name or another escape would
  // show within six characters
  std::vector<std::string> names = all_strings("_012vDx-", 6);
  for (const std::string& more : all_strings("_1aM", 8)) names.push_back(more);
  for (const char* more : {"x__y", "x_y", "_x", "v_x", "x_", "x__", "fields", "np", "EOF", "NULL", "M_PI", "M_1_PI",
                           "M_11_PI", "linux", "unix", "int", "int_", "Scalar", "Scalar_", "q", "q_", "v_0_x_", "x_1_",
                           "my model", "caf\xc3\xa9", "a\nb", "a\"b", "a::b"})
    names.push_back(more);
  std::map<std::string, std::string> name_of;
  for (const std::string& name : names) {
    const std::string id = cpp_identifier(name);
    ASSERT_TRUE(is_unreserved_identifier(id)) << "'" << name << "' -> '" << id << "'";
    // a name is kept only if it is plain; an escape ends in '_', which no plain name does
    if (id != name) {
      ASSERT_EQ(id.back(), '_') << "'" << name << "' -> '" << id << "'";
    }
    const auto [it, inserted] = name_of.emplace(id, name);
    ASSERT_TRUE(inserted || it->second == name) << "'" << name << "' and '" << it->second << "' -> '" << id << "'";
  }
  EXPECT_GT(name_of.size(), 300000u);
}

TEST(CppIdentifier, KeywordsAreNeverKept) {
  for (const char* keyword :
       {"alignas", "and", "auto", "bool", "char8_t", "class", "co_await", "concept", "consteval", "constinit",
        "decltype", "delete", "double", "export", "false", "final", "import", "int", "module", "new", "not",
        "nullptr", "operator", "override", "requires", "return", "static_assert", "this", "thread_local", "true",
        "typename", "union", "using", "void", "wchar_t", "xor_eq"})
    EXPECT_EQ(cpp_identifier(keyword), std::string(keyword) + "_");
}

// The identifiers of C++ source that are not qualified (after '.', '->' or '::'), outside
// comments, string literals and preprocessor lines.
std::set<std::string> unqualified_identifiers(const std::string& source) {
  std::set<std::string> out;
  std::istringstream lines(source);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(' ') != std::string::npos && line[line.find_first_not_of(' ')] == '#') continue;
    line = line.substr(0, line.find("//"));
    line = std::regex_replace(line, std::regex("\"([^\"\\\\]|\\\\.)*\""), "\"\"");
    static const std::regex identifier("(\\.|->|::)?\\s*\\b([A-Za-z_][A-Za-z0-9_]*)");
    for (auto it = std::sregex_iterator(line.begin(), line.end(), identifier); it != std::sregex_iterator(); ++it)
      if (!(*it)[1].matched) out.insert((*it)[2].str());
  }
  return out;
}

// Every name the generated code uses where a model's name could stand for it, in headers that
// have every part (constraints, forward dynamics, the recursions' M and F, linearization), is
// changed by the mangling: the list in cpp_identifier.cpp is complete.
TEST(CppIdentifier, ChangesEveryNameOfTheGeneratedCode) {
  std::set<std::string> names;
  auto collect = [&](const Model& model, const std::string& header) {
    std::set<std::string> own = {cpp_identifier(model.name), "eomgen_models"};  // the namespaces
    for (const Parameter& p : model.system.variables().parameters()) own.insert(cpp_identifier(p.name));
    static const std::regex numbered("[wk][0-9]+");  // locals and members of the Constants: see cpp_identifier.cpp
    for (const std::string& id : unqualified_identifiers(header))
      if (!own.count(id) && !std::regex_match(id, numbered)) names.insert(id);
  };
  for (const char* name : {"rolling_coin", "cart_pole", "knife_edge", "spacecraft_panel"}) {
    const Model model = load_model(testing::shipped_model_path(name));
    const ModelEquations eom = derive_equations(model);
    collect(model, emit_model(model, eom, linearize_symbolic(model, eom)).header);
  }
  const Model chain = load_model(testing::shipped_model_path("planar_chain"), {{"n", 8}});
  collect(chain, emit_model(chain, derive_equations(chain)).header);

  EXPECT_GT(names.size(), 80u);
  for (const std::string& name : names) {
    EXPECT_NE(cpp_identifier(name), name) << name << " is a name of the generated code: add it to cpp_identifier.cpp";
    // no escape can equal it
    EXPECT_TRUE(is_unreserved_identifier(name) && name.back() != '_') << name;
  }
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Every macro defined at the end of the simulation program's translation unit (the generated
// header, then simulation_main.hpp with the runtime, as simulate_command.cpp writes its
// driver), under -std=c++17 and -std=gnu++17 with simulate's compiler and flags, is changed by the
// mangling and is no escape: the list of header_macros.cpp is complete for these includes.
TEST(CppIdentifier, ChangesEveryMacroOfTheGeneratedAndSimulationHeaders) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("eomgen_cpp_identifier_macros_{}", ::getpid());
  fs::create_directories(dir);
  const Model model = load_model(testing::shipped_model_path("rolling_coin"));
  const ModelEquations eom = derive_equations(model);
  std::ofstream(dir / "model.hpp") << emit_model(model, eom, linearize_symbolic(model, eom)).header;
  std::ofstream(dir / "driver.cpp") << "#include \"model.hpp\"\n#include \"simulation_main.hpp\"\n";

  std::set<std::string> missing;
  std::size_t count = 0;
  for (const char* standard : {"-std=c++17", "-std=gnu++17"}) {
    const fs::path macros = dir / "macros.txt";
    namespace config = tools::build_config;
    const std::string command =
        fmt::format("'{}' {} {} -fno-fast-math -dM -E -I'{}' -I'{}' -I'{}' -I'{}' '{}' > '{}'", config::cxx_compiler,
                    config::cxx_flags, standard, dir.string(), config::source_simulation_program_dir,
                    config::source_runtime_include_dir, config::eigen_include_dir, (dir / "driver.cpp").string(),
                    macros.string());
    ASSERT_EQ(run(command), 0) << command;
    std::ifstream in(macros);
    for (std::string directive, name; in >> directive >> name; in.ignore(1 << 20, '\n')) {
      name = name.substr(0, name.find('('));
      ++count;
      if (cpp_identifier(name) == name) missing.insert(name);
      // an escape ends in '_' with no "__" and no leading '_': no macro may look like one
      if (is_unreserved_identifier(name)) {
        EXPECT_NE(name.back(), '_') << name;
      }
    }
  }
  EXPECT_GT(count, 3000u);
  std::string list;
  for (const std::string& name : missing) list += fmt::format("    \"{}\",\n", name);
  EXPECT_TRUE(missing.empty()) << "macros the mangling keeps; add them to generator/codegen/src/header_macros.cpp:\n"
                               << list;
  if (!HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace eomgen
