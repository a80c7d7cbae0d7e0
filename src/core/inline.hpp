// GRANWAVE_ALWAYS_INLINE: the contact kernel's forced inlining, one switch for all of it.
// The Release build inlines every piece of a contact pass into the pass (its speed depends on it).
// The sanitizer build (GRANWAVE_SANITIZE defines GRANWAVE_NO_FORCED_INLINE) compiles each piece once
// at -O0 instead: forced into every caller, one law's passes took GCC 12 over 4 min to instrument.
#pragma once

#if defined(GRANWAVE_NO_FORCED_INLINE)
#define GRANWAVE_ALWAYS_INLINE
#else
#define GRANWAVE_ALWAYS_INLINE __attribute__((always_inline))
#endif
