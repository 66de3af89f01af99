#pragma once
// Forced into the scene parser's sources in the fuzz build (fuzz/CMakeLists.txt), where toml++ is
// compiled from its headers: its internal assertions compile to nothing, as they do in Debian's
// libtomlplusplus.so, which the program links (built by GCC 12, which has no __builtin_assume,
// so TOML_ASSERT_ASSUME is no code there either). Otherwise the fuzzer would stop at toml++
// preconditions that malformed input breaks but that the library's release code then reports as
// syntax errors (e.g. "[&]", "a=[}"; upstream marzer/tomlplusplus#294). What is undefined there
// as well, an unreachable point reached, UBSan still reports.
#define TOML_ASSERT(expr) static_assert(true)
