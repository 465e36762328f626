//! The ladder's steps: forward (the best significant candidate added while there is one),
//! then swaps, backward elimination and the ladder rebuilt along the final set.

use super::*;

/// Forward: the best significant candidate added while there is one; the first step's ranking,
/// the model reached, and its last step's p value.
pub(super) fn forward(
    model: &Model,
    data: &Data,
    candidates: &[Arc<dyn Effect>],
    baseline: &Evaluated,
    f: &Folds,
    opts: &Options,
    repeatability: Option<&Repeatability>,
) -> Result<(Vec<Scored>, Evaluated, Option<f64>), DiagnoseError> {
    let mut ranking = Vec::new();
    let mut remaining: Vec<Arc<dyn Effect>> = candidates.to_vec();
    let mut current = baseline.clone();
    let mut last_p = None;
    for step in 0..opts.max_steps {
        if remaining.is_empty() {
            break;
        }
        let ranked = rank(model, data, &current, &remaining, f, opts.alpha, repeatability)?;
        let pick = ranked.iter().find(|s| s.significant).cloned();
        if step == 0 {
            ranking = ranked;
        }
        let Some(Scored {
            id,
            fit: Some(fit),
            kfold_rms,
            kfold_by_load: Some(kfold_by_load),
            loro_rms,
            p_value,
            ..
        }) = pick
        else {
            break;
        };
        remaining.retain(|e| e.id() != id);
        last_p = Some(p_value);
        current = Evaluated {
            fit,
            kfold: kfold_rms,
            kfold_by_load,
            loro: loro_rms,
        };
    }
    Ok((ranking, current, last_p))
}

/// Swaps and backward elimination, then the ladder rebuilt along the final set (onto `ladder`,
/// the effects that could not be a rung onto `dropped`); the model reached.
#[allow(clippy::too_many_arguments)]
pub(super) fn rebuild_ladder(
    model: &Model,
    data: &Data,
    current: Evaluated,
    candidates: &[Arc<dyn Effect>],
    baseline: Evaluated,
    ranking: &[Scored],
    f: &Folds,
    opts: &Options,
    repeatability: Option<&Repeatability>,
    ladder: &mut Vec<Rung>,
    dropped: &mut Vec<(String, String)>,
) -> Result<Evaluated, DiagnoseError> {
    let refined = refine(model, data, current, candidates, f, opts.alpha)?;
    let refined = best_pair(model, data, refined, ranking, candidates, f)?;
    let mut set = refined.effects();
    let mut cur = baseline;
    while !set.is_empty() {
        let mut tried: Vec<Evaluated> = Vec::with_capacity(set.len());
        for e in &set {
            let mut effects = cur.effects();
            effects.push(e.clone());
            let warm = if set.len() == 1 {
                &refined.fit.stack
            } else {
                &cur.fit.stack
            };
            tried.push(evaluate(model, data, effects, warm, f)?);
        }
        let mut refusals: Vec<Option<String>> = tried
            .iter()
            .zip(&set)
            .map(|(ev, e)| {
                refusal(
                    data,
                    &cur.fit,
                    &ev.fit,
                    repeatability,
                    load_of(data, &ev.fit, e.params().len()),
                )
            })
            .collect();
        let options: Vec<(f64, bool)> = tried
            .iter()
            .zip(&refusals)
            .map(|(ev, why)| (ev.score(), why.is_none()))
            .collect();
        let Some(i) = rung_choice(&options) else {
            break;
        };
        let ev = tried.swap_remove(i);
        let gone = set.remove(i);
        if let Some(why) = refusals.swap_remove(i) {
            // No effect of the set can be a rung here: the ladder stops, and says why.
            dropped.push((gone.id().to_string(), why));
            break;
        }
        let load = load_of(data, &ev.fit, gone.params().len());
        let (_, p) = f_test_on(data, &cur.fit, &ev.fit, gone.params().len(), load);
        ladder.push(ev.rung(data, Some(p)));
        cur = ev;
    }
    Ok(cur)
}
