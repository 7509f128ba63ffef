# ddish_module(NAME DEPS a b ...): a static library ddish_NAME from src/NAME/*.cpp.
# Public headers are included as "NAME/header.h" from src/.
function(ddish_module name)
  cmake_parse_arguments(M "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(sources)
    add_library(ddish_${name} STATIC ${sources})
    target_include_directories(ddish_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(ddish_${name} PUBLIC ${M_DEPS})
  else()  # header-only so far
    add_library(ddish_${name} INTERFACE)
    target_include_directories(ddish_${name} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(ddish_${name} INTERFACE ${M_DEPS})
  endif()
endfunction()

# ddish_tests(MODULE DEPS ...): one test binary per module from tests/MODULE/*.cpp.
function(ddish_tests name)
  cmake_parse_arguments(T "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cpp)
  if(NOT sources)
    return()
  endif()
  add_executable(test_${name} ${sources})
  if(TARGET ddish_${name})
    target_link_libraries(test_${name} PRIVATE ddish_${name})
  endif()
  target_link_libraries(test_${name} PRIVATE ${T_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(test_${name} PRIVATE
    DDISH_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    DDISH_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(test_${name} TEST_PREFIX "${name}." PROPERTIES LABELS ${name} DISCOVERY_TIMEOUT 60)
endfunction()
