// The figures of a program's --check plan that cosim check combines (the coupled cycle's first step and the
// number of cycles): with --plan-facts, a program's plan ends with one line "plan-facts: {JSON}".
#pragma once

#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

namespace cosim::app {

inline constexpr const char* kPlanFactsTag = "plan-facts: ";

inline void print_plan_facts(const nlohmann::json& facts) { std::cout << kPlanFactsTag << facts.dump() << "\n"; }

}  // namespace cosim::app
