// The plain runner (runAll): every selected case on every backend, one line per run, a cross-backend
// comparison per case when there are two backends, and an exit code. No test framework needed.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string_view>

#include "bricklight/conformance.h"

namespace bricklight::conformance {

namespace {
using Clock = std::chrono::steady_clock;

// "1.23 s", without touching the caller's stream formatting.
std::string secondsSince(Clock::time_point start) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f s", std::chrono::duration<double>(Clock::now() - start).count());
    return text;
}

bool selected(const Case& c, const std::vector<std::string>& filters) {
    if (filters.empty()) return true;
    for (const std::string& f : filters)
        if (std::string_view(c.name).find(f) != std::string_view::npos) return true;
    return false;
}

void printLines(std::ostream& out, const char* prefix, const std::vector<std::string>& lines) {
    for (const std::string& l : lines) out << "    " << prefix << l << '\n';
}

struct Tally {
    size_t runsPassed = 0, runsFailed = 0, comparisonsEqual = 0, comparisonsFailed = 0, runsWithNotes = 0;
};

// Compares the case's results on the first two backends; a comparison needs both runs to have passed and
// to have produced something to compare.
bool compareRuns(std::ostream& out, const Case& c, const Backend& a, const CaseResult& ra, const Backend& b,
                 const CaseResult& rb) {
    std::vector<std::string> problems;
    if (!ra.passed) problems.push_back("not compared: the case failed on " + a.name);
    if (!rb.passed) problems.push_back("not compared: the case failed on " + b.name);
    if (problems.empty()) {
        problems = compareOutputs(ra, rb);
        if (ra.outputs.empty()) problems.push_back("the case produced no outputs to compare");
    }
    out << (problems.empty() ? "passed" : "failed") << "  cross/" << c.name << " (" << a.name << " vs " << b.name
        << ")\n";
    printLines(out, "", problems);
    return problems.empty();
}
}  // namespace

int runAll(const std::vector<Backend>& backends, const RunOptions& options) {
    std::ostream& out = options.out ? *options.out : std::cout;
    if (backends.empty()) {
        out << "conformance: no backend to run\n";
        return 1;
    }
    std::vector<const Case*> chosen;
    for (const Case& c : cases())
        if (selected(c, options.filters)) chosen.push_back(&c);
    if (chosen.empty()) {
        out << "conformance: no case matches the filter(s)";
        for (const std::string& f : options.filters) out << " '" << f << "'";
        out << " (" << cases().size() << " cases)\n";
        return 1;
    }

    const Clock::time_point start = Clock::now();
    Tally tally;
    for (const Case* c : chosen) {
        std::vector<CaseResult> results;
        for (const Backend& b : backends) {
            const Clock::time_point caseStart = Clock::now();
            results.push_back(runCase(*c, b));
            const CaseResult& r = results.back();
            out << (r.passed ? "passed" : "failed") << "  " << b.name << '/' << c->name << " (" << secondsSince(caseStart)
                << ")\n";
            printLines(out, "", r.failures);
            printLines(out, "note: ", r.notes);
            (r.passed ? tally.runsPassed : tally.runsFailed)++;
            if (!r.notes.empty()) ++tally.runsWithNotes;
            out.flush();  // a long run shows its progress
        }
        if (backends.size() >= 2) {
            bool equal = compareRuns(out, *c, backends[0], results[0], backends[1], results[1]);
            (equal ? tally.comparisonsEqual : tally.comparisonsFailed)++;
            out.flush();
        }
    }

    out << "conformance: " << chosen.size() << " of " << cases().size() << " cases on";
    for (size_t i = 0; i < backends.size(); ++i) out << (i ? ", " : " ") << backends[i].name;
    out << ": " << tally.runsPassed << " runs passed, " << tally.runsFailed << " failed";
    if (backends.size() >= 2)
        out << "; " << tally.comparisonsEqual << " cross-backend comparisons passed, " << tally.comparisonsFailed
            << " failed";
    if (tally.runsWithNotes) out << "; " << tally.runsWithNotes << " runs with notes (checks skipped)";
    out << " (" << secondsSince(start) << ")\n";
    out.flush();
    return tally.runsFailed == 0 && tally.comparisonsFailed == 0 ? 0 : 1;
}

}  // namespace bricklight::conformance
