# High warnings on everything we compile; -Werror only where asked (CI), so a new compiler
# release does not break a user's build.
option(DPCR_WERROR "Treat warnings as errors" OFF)
add_library(dpcr_warnings INTERFACE)
target_compile_options(dpcr_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align
  $<$<BOOL:${DPCR_WERROR}>:-Werror>)
