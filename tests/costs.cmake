# tests/costs.txt as ctest COST properties (tests/CMakeLists.txt). Included twice: by CMake at
# configure time, with rayster_costs_tests naming the tests tests/CMakeLists.txt adds itself, and
# by ctest after the discovered tests, with rayster_tests_TESTS naming those. A name that is in
# neither list is left alone (TestCosts.EveryListedTestExists fails on it).
if(NOT DEFINED rayster_costs_tests)
  set(rayster_costs_tests ${rayster_tests_TESTS})
endif()
file(STRINGS "${rayster_costs_file}" rayster_costs REGEX "^[^#]")
foreach(rayster_cost_entry IN LISTS rayster_costs)
  if(NOT rayster_cost_entry MATCHES "^([0-9]+(\\.[0-9]+)?) (.+)$")
    message(WARNING "${rayster_costs_file}: not 'SECONDS NAME': ${rayster_cost_entry}")
    continue()
  endif()
  set(rayster_cost_seconds ${CMAKE_MATCH_1})
  set(rayster_cost_name "${CMAKE_MATCH_3}")
  list(FIND rayster_costs_tests "${rayster_cost_name}" rayster_cost_found)
  if(rayster_cost_found GREATER -1)
    set_tests_properties("${rayster_cost_name}" PROPERTIES COST ${rayster_cost_seconds})
  endif()
endforeach()
unset(rayster_costs_tests)
