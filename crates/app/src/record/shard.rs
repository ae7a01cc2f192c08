//! Which share of the frames one run renders: `--shard I/N`, or the index of a Slurm
//! array task or a Kubernetes indexed Job from the environment. Shard `I` of `N` takes
//! the `I`-th of `N` contiguous, nearly equal runs of the selected frames, so that
//! neighbouring frames (which share tables) stay on one machine.

use std::ops::Range;

use anyhow::{Context, bail};

/// The most shards a run may be split into.
pub const MAX_SHARDS: u64 = 1_000_000;

/// Shard `index` of `count` (`index < count`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// The whole run.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// `index` of `count`, checked; `what` names where they came from in errors.
    pub fn new(index: u64, count: u64, what: &str) -> anyhow::Result<Shard> {
        if !(1..=MAX_SHARDS).contains(&count) {
            bail!("{what}: the shard count {count} must be 1 to {MAX_SHARDS}");
        }
        if index >= count {
            bail!(
                "{what}: shard {index} of {count} does not exist; shards count from 0 to {}",
                count - 1
            );
        }
        Ok(Shard { index, count })
    }

    /// `I/N` as `--shard` takes it.
    pub fn parse(text: &str) -> anyhow::Result<Shard> {
        let what = format!("--shard {text}");
        let (index, count) = text
            .split_once('/')
            .with_context(|| format!("{what}: expected I/N, e.g. 0/4 (shard I of N, from 0)"))?;
        let number = |s: &str, name: &str| {
            s.trim()
                .parse::<u64>()
                .with_context(|| format!("{what}: {name} '{s}' is not a whole number >= 0"))
        };
        Shard::new(number(index, "I")?, number(count, "N")?, &what)
    }

    /// The shard of a run: `flag` (`--shard`) first, then a Slurm array task, then a
    /// Kubernetes indexed Job (its count from `count_flag`, `--shard-count`, or
    /// `ATMOS_SHARD_COUNT`), else the whole run. `env` looks a variable up.
    pub fn choose(
        flag: Option<Shard>,
        count_flag: Option<u64>,
        env: impl Fn(&str) -> Option<String>,
    ) -> anyhow::Result<Shard> {
        if let Some(shard) = flag {
            return Ok(shard);
        }
        if let Some(shard) = Shard::from_slurm(&env)? {
            return Ok(shard);
        }
        if let Some(shard) = Shard::from_kubernetes(count_flag, &env)? {
            return Ok(shard);
        }
        if let Some(count) = count_flag {
            bail!(
                "--shard-count {count} needs JOB_COMPLETION_INDEX (a Kubernetes indexed Job) or --shard I/N"
            );
        }
        Ok(Shard::ALL)
    }

    /// From `SLURM_ARRAY_TASK_ID` with `SLURM_ARRAY_TASK_COUNT`, or with
    /// `SLURM_ARRAY_TASK_MIN`, `_MAX` (and `_STEP`): array `--array=0-7` is 8 shards.
    fn from_slurm(env: &impl Fn(&str) -> Option<String>) -> anyhow::Result<Option<Shard>> {
        let Some(id) = env_number(env, "SLURM_ARRAY_TASK_ID")? else {
            return Ok(None);
        };
        let min = env_number(env, "SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
        let step = env_number(env, "SLURM_ARRAY_TASK_STEP")?
            .unwrap_or(1)
            .max(1);
        if id < min || (id - min) % step != 0 {
            bail!(
                "SLURM_ARRAY_TASK_ID={id} is not one of the array's tasks (from SLURM_ARRAY_TASK_MIN={min} in steps of {step})"
            );
        }
        let count = match (
            env_number(env, "SLURM_ARRAY_TASK_COUNT")?,
            env_number(env, "SLURM_ARRAY_TASK_MAX")?,
        ) {
            (Some(count), _) => count,
            (None, Some(max)) if max >= min => (max - min) / step + 1,
            _ => bail!(
                "SLURM_ARRAY_TASK_ID={id} needs SLURM_ARRAY_TASK_COUNT or SLURM_ARRAY_TASK_MAX to know how many shards there are"
            ),
        };
        Shard::new((id - min) / step, count, "the Slurm array task").map(Some)
    }

    /// From `JOB_COMPLETION_INDEX`, the count from `--shard-count` or
    /// `ATMOS_SHARD_COUNT` (the Job's `completions`).
    fn from_kubernetes(
        count_flag: Option<u64>,
        env: &impl Fn(&str) -> Option<String>,
    ) -> anyhow::Result<Option<Shard>> {
        let Some(index) = env_number(env, "JOB_COMPLETION_INDEX")? else {
            return Ok(None);
        };
        let count = match count_flag {
            Some(count) => count,
            None => env_number(env, "ATMOS_SHARD_COUNT")?.with_context(|| {
                format!(
                    "JOB_COMPLETION_INDEX={index} needs the number of shards: --shard-count N or ATMOS_SHARD_COUNT=N (the Job's completions)"
                )
            })?,
        };
        Shard::new(index, count, "the Kubernetes indexed Job").map(Some)
    }

    /// This shard's part of `frames`: contiguous, sizes differing by at most one.
    pub fn part(&self, frames: Range<u64>) -> Range<u64> {
        let len = u128::from(frames.end - frames.start);
        let at = |i: u64| frames.start + (len * u128::from(i) / u128::from(self.count)) as u64;
        at(self.index)..at(self.index + 1)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// A whole number from the environment variable `name`, if it is set.
fn env_number(env: &impl Fn(&str) -> Option<String>, name: &str) -> anyhow::Result<Option<u64>> {
    env(name)
        .map(|v| {
            v.trim()
                .parse::<u64>()
                .with_context(|| format!("{name}='{v}' is not a whole number >= 0"))
        })
        .transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env_of(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let pairs: Vec<(String, String)> = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| k == name)
                .map(|(_, v)| v.clone())
        }
    }

    fn err(result: anyhow::Result<Shard>) -> String {
        format!("{:#}", result.unwrap_err())
    }

    #[test]
    fn the_flag_parses_and_is_checked() {
        assert_eq!(Shard::parse("1/2").unwrap(), Shard { index: 1, count: 2 });
        assert!(err(Shard::parse("2/2")).contains("shard 2 of 2 does not exist"));
        assert!(err(Shard::parse("0/0")).contains("shard count 0 must be 1 to"));
        assert!(err(Shard::parse("1")).contains("expected I/N"));
        assert!(err(Shard::parse("-1/2")).contains("I '-1' is not a whole number"));
        assert!(err(Shard::parse("0/x")).contains("N 'x' is not a whole number"));
    }

    #[test]
    fn parts_cover_the_frames_once_in_order() {
        for count in 1..9 {
            for frames in [0..0, 0..1, 3..10, 5..105] {
                let mut next = frames.start;
                for index in 0..count {
                    let part = Shard { index, count }.part(frames.clone());
                    assert_eq!(part.start, next);
                    assert!(part.end - part.start <= (frames.end - frames.start) / count + 1);
                    next = part.end;
                }
                assert_eq!(next, frames.end);
            }
        }
    }

    #[test]
    fn the_flag_wins_over_the_environment() {
        let env = env_of(&[
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]);
        let flag = Shard { index: 0, count: 2 };
        assert_eq!(Shard::choose(Some(flag), None, &env).unwrap(), flag);
        assert_eq!(Shard::choose(None, None, env_of(&[])).unwrap(), Shard::ALL);
    }

    #[test]
    fn slurm_arrays_give_the_shard() {
        let shard = |pairs: &[(&str, &str)]| Shard::choose(None, None, env_of(pairs));
        let count = shard(&[
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]);
        assert_eq!(count.unwrap(), Shard { index: 3, count: 4 });
        let min_max = shard(&[
            ("SLURM_ARRAY_TASK_ID", "12"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_MAX", "17"),
        ]);
        assert_eq!(min_max.unwrap(), Shard { index: 2, count: 8 });
        let stepped = shard(&[
            ("SLURM_ARRAY_TASK_ID", "4"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_MAX", "6"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ]);
        assert_eq!(stepped.unwrap(), Shard { index: 2, count: 4 });
        assert!(err(shard(&[("SLURM_ARRAY_TASK_ID", "1")])).contains("SLURM_ARRAY_TASK_COUNT"));
        assert!(
            err(shard(&[("SLURM_ARRAY_TASK_ID", "x")]))
                .contains("SLURM_ARRAY_TASK_ID='x' is not a whole number")
        );
        assert!(
            err(shard(&[
                ("SLURM_ARRAY_TASK_ID", "4"),
                ("SLURM_ARRAY_TASK_COUNT", "4")
            ]))
            .contains("the Slurm array task: shard 4 of 4 does not exist")
        );
    }

    #[test]
    fn kubernetes_indexed_jobs_give_the_shard() {
        let env = env_of(&[("JOB_COMPLETION_INDEX", "1"), ("ATMOS_SHARD_COUNT", "3")]);
        assert_eq!(
            Shard::choose(None, None, &env).unwrap(),
            Shard { index: 1, count: 3 }
        );
        assert_eq!(
            Shard::choose(None, Some(5), &env).unwrap(),
            Shard { index: 1, count: 5 }
        );
        let no_count = Shard::choose(None, None, env_of(&[("JOB_COMPLETION_INDEX", "1")]));
        assert!(err(no_count).contains("--shard-count N or ATMOS_SHARD_COUNT=N"));
        assert!(
            err(Shard::choose(None, Some(2), env_of(&[]))).contains("needs JOB_COMPLETION_INDEX")
        );
    }
}
