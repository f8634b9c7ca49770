# Sanitizer builds (ASan+UBSan, or TSan); applied to every target in the tree.
if(PLANESKETCH_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
  # GCC 12 reports false maybe-uninitialized warnings inside CGAL's headers when instrumenting
  # (seen in zone_arrangement.cpp via CGAL/Epic_converter.h); they would break -Werror builds.
  add_compile_options(-Wno-maybe-uninitialized)
endif()
if(PLANESKETCH_TSAN)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
