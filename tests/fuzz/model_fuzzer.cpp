// libFuzzer target: the bytes are the text of a model file, given to the language's entry point
// parse_model (lexer, parser, elaborator and the checks on the whole model). A SourceError
// ("fuzz.eom:LINE:COL: error: ...") is the documented answer to bad input and ends the run
// quietly. Everything else is a finding: another exception (an eomgen::Error without a position,
// an InternalError, a GiNaC or standard-library exception such as "floating point overflow" or
// std::bad_alloc), a message that calls itself an internal error, and whatever the sanitizers and
// libFuzzer catch (a crash, a stack overflow from deep nesting, undefined behaviour, a leak, a
// timeout, memory past -rss_limit_mb).
//
// The target stops at the Model: it does not derive the equations. A derivation of a random
// model can take seconds to minutes (GiNaC expands what the fuzzer nests), which would take the
// speed from thousands of inputs a second to a few and report slowness as timeouts; the
// derivation's input is a Model that this layer has checked, and its tests cover it.
//
// Built by -DEOMGEN_FUZZ=ON with clang (tests/fuzz/CMakeLists.txt); run by scripts/fuzz.sh.
#include <cxxabi.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "eomgen/base/error.hpp"
#include "eomgen/language/model_file.hpp"

namespace {

[[noreturn]] void finding(const char* kind, const std::string& what) {
  std::fprintf(stderr, "==eomgen fuzz finding: %s: %s\n", kind, what.c_str());
  std::abort();  // libFuzzer saves the input as crash-<sha1>
}

std::string type_name(const std::type_info& type) {
  int status = 0;
  char* demangled = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  std::string name = status == 0 && demangled ? demangled : type.name();
  std::free(demangled);
  return name;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    eomgen::parse_model(text, "fuzz.eom");
  } catch (const eomgen::SourceError& e) {
    const std::string what = e.what();
    if (what.rfind("fuzz.eom:", 0) != 0) finding("a SourceError without the file's position", what);
    if (what.find("internal error") != std::string::npos) finding("a SourceError that reports an internal error", what);
  } catch (const eomgen::Error& e) {
    finding("an eomgen::Error without a position (parse_model promises a SourceError)", e.what());
  } catch (const eomgen::InternalError& e) {
    finding("an InternalError", e.what());
  } catch (const std::exception& e) {
    finding(("an exception of type " + type_name(typeid(e))).c_str(), e.what());
  } catch (...) {
    finding("an exception of unknown type", "");
  }
  return 0;
}
