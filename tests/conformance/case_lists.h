// The kit's case lists, one function per cases_*.cpp. cases() (case_list.cpp) calls each of them: a function
// that is called keeps its file's cases in a program that links the kit as a static library, where cases
// that registered themselves from static initialisers would be dropped by the linker.
#pragma once

#include <vector>

#include "bricklight/conformance.h"

namespace bricklight::conformance {

void appendComputeCases(std::vector<Case>& out);    // cases_compute.cpp
void appendDrawCases(std::vector<Case>& out);       // cases_draws.cpp
void appendFormatCases(std::vector<Case>& out);     // cases_formats.cpp
void appendHazardCases(std::vector<Case>& out);     // cases_hazards.cpp
void appendIndirectCases(std::vector<Case>& out);   // cases_indirect.cpp
void appendSamplerCases(std::vector<Case>& out);    // cases_samplers.cpp
void appendTransferCases(std::vector<Case>& out);   // cases_transfers.cpp
void appendViewCases(std::vector<Case>& out);       // cases_views.cpp

}  // namespace bricklight::conformance

// A case list entry named after its function: BL_CASE(storage_buffer_fill, "storageBuffers, constants").
#define BL_CASE(function, covers) ::bricklight::conformance::Case{#function, covers, function}
