// CPU planning of an update. Cascades follow the centre in whole voxels; the slabs that enter a window are
// rebuilt (their toroidal slots held the voxels that left). Dirty world boxes (instances added, moved,
// removed; dynamic instances every update) become per-cascade jobs, clipped to the window. Jobs are
// taken in order while the budgets allow; the rest wait for the next update.
#include <algorithm>
#include <cmath>

#include "sdf_scene_impl.h"

namespace bricklight::sdf::detail {

namespace {
constexpr int kRes = int(kCascadeResolution);
}

bool SdfSceneImpl::clipToCascade(Job& job) const {
    const glm::ivec3 lo = cascades_[job.cascade].origin, hi = lo + kRes;
    job.min = glm::max(job.min, lo);
    job.max = glm::min(job.max, hi);
    return glm::all(glm::lessThan(job.min, job.max));
}

void SdfSceneImpl::scrollCascades(const glm::vec3& center) {
    for (uint32_t c = 0; c < desc_.cascadeCount; ++c) {
        const float vs = voxelSize(c);
        const glm::ivec3 next = glm::ivec3(glm::floor(center / vs)) - kRes / 2;
        CascadeState& cs = cascades_[c];
        if (!cs.placed) {
            cs.origin = next;
            cs.placed = true;
            pending_.push_back({c, next, next + kRes});
            continue;
        }
        const glm::ivec3 old = cs.origin;
        if (next == old) continue;
        cs.origin = next;
        // The part of the new window outside the old one, as up to three disjoint slabs.
        glm::ivec3 lo = next, hi = next + kRes;
        for (int axis = 0; axis < 3; ++axis) {
            const int oldLo = old[axis], oldHi = old[axis] + kRes;
            Job slab{c, lo, hi};
            if (next[axis] > old[axis]) {
                slab.min[axis] = std::max(oldHi, lo[axis]);
                if (slab.min[axis] < hi[axis]) pending_.push_back(slab);
                hi[axis] = std::min(hi[axis], oldHi);
            } else if (next[axis] < old[axis]) {
                slab.max[axis] = std::min(oldLo, hi[axis]);
                if (lo[axis] < slab.max[axis]) pending_.push_back(slab);
                lo[axis] = std::max(lo[axis], oldLo);
            }
            if (lo[axis] >= hi[axis]) break;  // moved by a whole window: the first slab was all of it
        }
    }
}

// Triangles of the static (or dynamic) instances a job needs that are not chosen yet; marks and lists them.
uint32_t SdfSceneImpl::trianglesFor(const Job& job, bool dynamic, std::vector<char>& chosen, std::vector<uint32_t>& picked) const {
    const float vs = voxelSize(job.cascade), b = band(job.cascade);
    const glm::vec3 lo = glm::vec3(job.min) * vs - b, hi = glm::vec3(job.max) * vs + b;
    uint32_t total = 0;
    size_t index = 0;
    for (const auto& [id, inst] : instances_) {
        const size_t i = index++;
        if (chosen[i] || inst.dynamic != dynamic || inst.maxCascade < job.cascade) continue;
        if (glm::any(glm::lessThan(inst.bounds.max, lo)) || glm::any(glm::greaterThan(inst.bounds.min, hi))) continue;
        total += inst.moverGrid >= 0 ? moverChunks(inst, 0.0f, 0, nullptr) : meshes_.at(inst.mesh.id).triangleCount;
        picked.push_back(uint32_t(i));
    }
    return total;
}

// Merges jobs of one cascade pairwise, the pair whose bounding box adds the least volume first, until at
// most `cap` remain. Keeps the progress of split work (unlike one box per cascade).
// Drops jobs that another job of the same cascade contains (a dynamic instance that did not move gives
// the same box twice; retried work repeats boxes).
static void dropContainedJobs(std::vector<Job>& jobs) {
    for (size_t i = 0; i < jobs.size(); ++i)
        for (size_t k = 0; k < jobs.size(); ++k)
            if (i != k && jobs[i].cascade == jobs[k].cascade && glm::all(glm::lessThanEqual(jobs[k].min, jobs[i].min)) &&
                glm::all(glm::lessThanEqual(jobs[i].max, jobs[k].max)) && (jobs[k].invalidated || !jobs[i].invalidated)) {
                jobs.erase(jobs.begin() + long(i));
                --i;
                break;
            }
}

static void mergeJobs(std::vector<Job>& jobs, size_t cap) {
    if (jobs.size() <= cap) return;
    dropContainedJobs(jobs);
    while (jobs.size() > cap) {
        size_t bi = 0, bj = 0;
        int64_t best = INT64_MAX;
        for (size_t i = 0; i < jobs.size(); ++i)
            for (size_t k = i + 1; k < jobs.size(); ++k) {
                if (jobs[i].cascade != jobs[k].cascade) continue;
                Job u{jobs[i].cascade, glm::min(jobs[i].min, jobs[k].min), glm::max(jobs[i].max, jobs[k].max)};
                const int64_t added = int64_t(u.voxels()) - int64_t(jobs[i].voxels()) - int64_t(jobs[k].voxels());
                if (added < best) {
                    best = added;
                    bi = i;
                    bj = k;
                }
            }
        if (best == INT64_MAX) return;  // one job per cascade left
        jobs[bi].min = glm::min(jobs[bi].min, jobs[bj].min);
        jobs[bi].max = glm::max(jobs[bi].max, jobs[bj].max);
        jobs[bi].invalidated = jobs[bi].invalidated && jobs[bj].invalidated;
        jobs.erase(jobs.begin() + long(bj));
    }
}

// Takes candidate jobs in order while the budgets allow (a job alone over one is split); the rest wait in
// pending_ (a full job) or become full jobs there (an overlay job: its voxels are invalidated now, so that no
// composite shows a dynamic instance where it was, and built from scratch later).
void SdfSceneImpl::planRound(std::vector<Job> candidates, bool dynamic, Round& round, uint32_t& changedCascades) {
    std::vector<char> chosen(instances_.size(), 0);
    std::vector<uint32_t> instanceOrder;
    instanceOrder.reserve(instances_.size());
    for (const auto& [id, inst] : instances_) instanceOrder.push_back(id);
    const Budgets& budgets = desc_.budgets;
    bool full = false;
    for (size_t k = 0; k < candidates.size(); ++k) {
        Job job = candidates[k];
        if (!clipToCascade(job)) continue;  // scrolled out of its cascade
        if (full) {
            pending_.push_back(job);
            continue;
        }
        std::vector<uint32_t> picked;
        const uint32_t extra = trianglesFor(job, dynamic, chosen, picked);
        const bool fits = round.jobs.size() < budgets.maxJobsPerUpdate &&
                          round.voxels + job.voxels() <= std::min<uint64_t>(budgets.maxVoxelsPerUpdate, adaptiveVoxelLimit_) &&
                          uint64_t(round.triangles) + extra <= budgets.maxTrianglesPerUpdate;
        if (!fits) {
            // A job alone over a budget is split in two along its longest side until it fits.
            const glm::ivec3 size = job.max - job.min;
            const bool alone = round.jobs.empty();
            if (alone && job.voxels() > 1) {
                const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
                Job a = job, b = job;
                a.max[axis] = b.min[axis] = job.min[axis] + size[axis] / 2;
                candidates.insert(candidates.begin() + long(k) + 1, {a, b});
                continue;
            }
            if (alone) {
                if (!oversizeReported_)
                    fail(ErrorCode::OverBudget, "one voxel of cascade " + std::to_string(job.cascade) + " needs " + std::to_string(extra) +
                         " triangles, more than maxTrianglesPerUpdate (" + std::to_string(budgets.maxTrianglesPerUpdate) +
                         "): it stays unbuilt (traced through the next cascade); raise the budget");
                oversizeReported_ = true;
                if (dynamic) pending_.push_back(job);  // its old composite must not stay
                continue;
            }
            full = true;
            pending_.push_back(job);
            continue;
        }
        for (uint32_t i : picked) {
            chosen[i] = 1;
            round.instances.push_back(instanceOrder[i]);
            const Instance& inst = instances_.at(instanceOrder[i]);
            if (inst.moverGrid < 0) continue;
            ++round.movers;
            round.moverChunks += moverChunks(inst, 0.0f, 0, nullptr);
        }
        round.triangles += extra;
        round.voxels += job.voxels();
        changedCascades |= 1u << job.cascade;
        round.jobs.push_back(job);
    }
}

Plan SdfSceneImpl::planUpdate(UpdateReport& report) {
    // Per cascade up to its highest, the voxels whose closed box (its lattice reaches the far faces) comes
    // within the band of a box.
    auto jobsFor = [&](const WorldBox& box, uint32_t maxCascade, std::vector<Job>& out) {
        for (uint32_t c = 0; c <= std::min(maxCascade, desc_.cascadeCount - 1); ++c) {
            const float vs = voxelSize(c), b = band(c);
            out.push_back({c, glm::ivec3(glm::ceil((box.min - b) / vs)) - 1, glm::ivec3(glm::floor((box.max + b) / vs)) + 1});
        }
    };
    // Dynamic instances: their old and new footprints are the overlay, every update — except those that cannot
    // have changed: the same transform and a mesh from CPU arrays (its vertices are the scene's, fixed; a mesh in
    // the application's buffers may deform under the same transform). Those stay as built, unless a full job
    // rebuilds their voxels (below).
    std::vector<Job> overlay;
    std::vector<const Instance*> still;
    changes_.clear();
    for (const WorldBox& b : dirtyBoxes_) changes_.push_back({b.min, b.max});
    for (auto& [id, inst] : instances_)
        if (inst.dynamic) {
            if (inst.built && inst.transform == inst.builtTransform && meshes_.at(inst.mesh.id).owned) {
                still.push_back(&inst);
                continue;
            }
            if (inst.built) {
                jobsFor(inst.builtBounds, inst.maxCascade, overlay);
                changes_.push_back({inst.builtBounds.min, inst.builtBounds.max});
            }
            jobsFor(inst.bounds, inst.maxCascade, overlay);
            changes_.push_back({inst.bounds.min, inst.bounds.max});
            inst.builtBounds = inst.bounds;
            inst.builtTransform = inst.transform;
            inst.built = true;
        }
    std::vector<Job> candidates = std::move(pending_);
    pending_.clear();
    for (size_t i = 0; i < dirtyBoxes_.size(); ++i) jobsFor(dirtyBoxes_[i], dirtyMaxCascade_[i], candidates);
    dirtyBoxes_.clear();
    dirtyMaxCascade_.clear();
    if (candidates.size() <= 4096) dropContainedJobs(candidates);  // quadratic: skipped for floods

    Plan plan;
    planRound(std::move(candidates), false, plan.full, plan.changedCascades);
    // A full job builds the static field alone: a still dynamic instance in its voxels is composited again.
    for (const Instance* inst : still) {
        std::vector<Job> footprint;
        jobsFor(inst->bounds, inst->maxCascade, footprint);
        for (const Job& f : footprint)
            for (const Job& j : plan.full.jobs) {
                if (j.cascade != f.cascade) continue;
                Job both{f.cascade, glm::max(f.min, j.min), glm::min(f.max, j.max)};
                if (glm::all(glm::lessThan(both.min, both.max))) overlay.push_back(both);
            }
    }
    if (overlay.size() <= 4096) dropContainedJobs(overlay);
    planRound(std::move(overlay), true, plan.overlay, plan.changedCascades);
    const Budgets& budgets = desc_.budgets;
    // Jobs deferred for the first time are invalidated now, so that no voxel shows what its toroidal slot
    // held before (or geometry that moved away); tracing falls to the next cascade there until they are
    // built. Too many: neighbours are merged (invalidating and rebuilding more than needed is safe).
    std::vector<Job> fresh, waiting;
    for (const Job& j : pending_) (j.invalidated ? waiting : fresh).push_back(j);
    mergeJobs(fresh, budgets.maxJobsPerUpdate);
    for (Job& j : fresh) j.invalidated = true;
    plan.invalidateOnly = fresh;
    for (const Job& j : fresh) plan.changedCascades |= 1u << j.cascade;
    pending_ = std::move(waiting);
    pending_.insert(pending_.end(), fresh.begin(), fresh.end());
    mergeJobs(pending_, 64 * size_t(budgets.maxJobsPerUpdate));
    report.jobs = uint32_t(plan.full.jobs.size() + plan.overlay.jobs.size());
    report.voxels = uint32_t(plan.full.voxels + plan.overlay.voxels);
    report.instancesGathered = uint32_t(plan.full.instances.size() + plan.overlay.instances.size());
    report.trianglesGathered = plan.full.triangles + plan.overlay.triangles - plan.overlay.moverChunks;
    report.overlayJobs = uint32_t(plan.overlay.jobs.size());
    report.overlayVoxels = uint32_t(plan.overlay.voxels);
    report.overlayTrianglesGathered = plan.overlay.triangles - plan.overlay.moverChunks;
    report.moverGridInstances = plan.overlay.movers;
    report.jobsDeferred = uint32_t(pending_.size());
    for (const Job& j : pending_) report.voxelsDeferred += uint32_t(j.voxels());
    return plan;
}

}  // namespace bricklight::sdf::detail
