# Warnings as an interface target (vk-bootstrap's habit). Every project target links it.
add_library(planesketch_warnings INTERFACE)
target_compile_options(planesketch_warnings INTERFACE
  -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow -Wnon-virtual-dtor
  -Wno-unused-parameter)
if(PLANESKETCH_WERROR)
  target_compile_options(planesketch_warnings INTERFACE -Werror)
endif()
