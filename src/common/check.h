// Invariant checks (pbrt style). A failed CHECK is a bug in shellmarch, never a user error: user
// errors throw sm::Error with context instead (see error.h).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace sm::detail {
[[noreturn]] void checkFailed(const char* file, int line, const char* expr, const std::string& msg);
}  // namespace sm::detail

#define SM_CHECK(cond)                                                     \
  do {                                                                     \
    if (!(cond)) [[unlikely]]                                              \
      ::sm::detail::checkFailed(__FILE__, __LINE__, #cond, std::string()); \
  } while (0)

#define SM_CHECK_MSG(cond, msg)                                                 \
  do {                                                                          \
    if (!(cond)) [[unlikely]] {                                                 \
      std::ostringstream sm_check_os_;                                          \
      sm_check_os_ << msg;                                                      \
      ::sm::detail::checkFailed(__FILE__, __LINE__, #cond, sm_check_os_.str()); \
    }                                                                           \
  } while (0)

#define SM_CHECK_OP(a, op, b)                                                               \
  do {                                                                                      \
    const auto& sm_a_ = (a);                                                                \
    const auto& sm_b_ = (b);                                                                \
    if (!(sm_a_ op sm_b_)) [[unlikely]] {                                                   \
      std::ostringstream sm_check_os_;                                                      \
      sm_check_os_ << sm_a_ << " vs " << sm_b_;                                             \
      ::sm::detail::checkFailed(__FILE__, __LINE__, #a " " #op " " #b, sm_check_os_.str()); \
    }                                                                                       \
  } while (0)

#define SM_CHECK_EQ(a, b) SM_CHECK_OP(a, ==, b)
#define SM_CHECK_NE(a, b) SM_CHECK_OP(a, !=, b)
#define SM_CHECK_LT(a, b) SM_CHECK_OP(a, <, b)
#define SM_CHECK_LE(a, b) SM_CHECK_OP(a, <=, b)
#define SM_CHECK_GT(a, b) SM_CHECK_OP(a, >, b)
#define SM_CHECK_GE(a, b) SM_CHECK_OP(a, >=, b)

#ifdef NDEBUG
#define SM_DCHECK(cond) \
  do {                  \
  } while (0)
#else
#define SM_DCHECK(cond) SM_CHECK(cond)
#endif
