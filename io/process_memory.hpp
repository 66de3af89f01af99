#pragma once
// The memory the running process has held at most (its peak resident set, getrusage's ru_maxrss),
// for the run summary: what a user needs to know before refining a model further. Of the whole
// process, so a run made inside a longer-lived program (the tests) reports that program's peak.
namespace isomuscle::io {

// MiB; NaN where the system does not say.
double peak_resident_mebibytes();

}  // namespace isomuscle::io
