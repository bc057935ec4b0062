#pragma once

#include <sylva/farm/Farm.hpp>

#include <string>
#include <vector>

/**
 * Slurm's own client commands (`sbatch`, `scontrol`, `scancel`), run as programs: the farm's only contact
 * with the scheduler. They read $SLURM_CONF or the site's configuration, as they would for the user.
 */
namespace sylva::farm {

/**
 * Checks that Slurm's client commands are on $PATH; throws sylva::Error "sbatch not found on PATH: …" naming
 * the package and `--dry-run` when not. Called before anything is written or submitted.
 */
void requireSlurm();

/** Whether Slurm's client commands are on $PATH (status works without them, from the files alone). */
bool slurmAvailable();

/**
 * Submits the farm's array for `tasks` (with its encode job when the farm encodes and `encode`), appends the
 * submission to `farm.submissions` and saves farm.json. Throws sylva::Error with sbatch's message when a
 * submission fails (an encode job that fails to submit cancels the array just submitted).
 */
Submission submit(Farm& farm, const std::vector<int>& tasks, bool encode);

/** Submits only the encode job (every frame done, the GIF/MP4 missing); recorded like submit(). */
Submission submitEncode(Farm& farm);

/**
 * What Slurm knows of the farm's jobs (`scontrol -o show job` for each submission's array and encode job).
 * Jobs Slurm no longer holds (past MinJobAge) are left out: the frames on disk still say what is done.
 */
std::vector<TaskState> queryFarm(const Farm& farm);

/** Cancels every pending or running job of the farm (`scancel`); returns the job ids cancelled. */
std::vector<std::string> cancelFarm(const Farm& farm);

} // namespace sylva::farm
