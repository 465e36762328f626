//! A residual pattern in words ("thrust over-predicted by 12 % on average (RMS 14 %). Largest
//! at J > 0.50 (+18 % there, +6 % elsewhere): ..."): each finding of
//! `propbet_diagnose::signature` said, with the candidate effects that can make it.

use propbet_diagnose::signature::{EffectList, Part, Regime, Relation, Shows, Signature, Unaffected, QUIET};

fn pct(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
}

/// `s` with its first letter a capital.
fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next().map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
}

/// What the cause of an RPM trend is, by where it shows.
fn rpm_cause(regime: Regime) -> &'static str {
    match regime {
        Regime::Both => " (a Reynolds-number effect on the sections; Mach at high tip speeds)",
        Regime::ForwardOnly => {
            " (what moves with Reynolds number at the small angles of forward flight and not near \
             stall: the sections' zero-lift angle, a laminar bubble's camber; or an airspeed off by a \
             constant, J off by dv/(nD), nothing statically; propbet's docs/studies/re-zero-lift.toml \
             and airspeed-offset.toml are user effects to test each)"
        }
        Regime::StaticOnly => {
            " (what moves with Reynolds number near stall, where the static blade works, and not at \
             the small angles of forward flight: the sections' maximum lift and stall)"
        }
    }
}

/// What thrust against torque says about the cause.
fn physics(relation: Relation) -> &'static str {
    match relation {
        Relation::Opposite => {
            "in opposite directions: the sections' drag (more drag, less thrust and more torque) or a load \
             on the balance, not an angle, the inflow, the air or the RPM, which move both the same way"
        }
        Relation::TorqueMore => "the same way, torque more than twice as much: the sections' drag more than their lift",
        Relation::ThrustMore => {
            "the same way, thrust more than twice as much: the thrust a power makes (the inflow, the tip \
             loss) or a load on the balance more than the sections' drag"
        }
        Relation::Similar => {
            "the same way by similar amounts: what changes the angles, the inflow, the air or the RPM moves both"
        }
    }
}

/// A part's own sentence, without its effects or full stop (not capitalised).
pub fn part_sentence(s: &Signature, shows: &Shows) -> String {
    let name = &s.quantity;
    match shows {
        Shows::Quiet => format!(
            "{name} within {:.0} % everywhere (RMS {:.1} %)",
            100.0 * QUIET,
            100.0 * s.rms
        ),
        Shows::Bias => format!(
            "{name} {} by {:.1} % on average (RMS {:.1} %)",
            if s.mean > 0.0 {
                "over-predicted"
            } else {
                "under-predicted"
            },
            100.0 * s.mean.abs(),
            100.0 * s.rms
        ),
        Shows::AgainstJ {
            median_j,
            above,
            there,
            elsewhere,
            cause,
        } => {
            let side = if *above {
                format!("J > {median_j:.2}")
            } else {
                format!("J <= {median_j:.2}")
            };
            let mut t = format!(
                "largest at {side} ({} there, {} elsewhere)",
                pct(*there),
                pct(*elsewhere)
            );
            if *cause {
                t.push_str(": an error that changes with J at fixed RPM comes from the angles or the inflow");
            }
            t
        }
        Shows::WithRpm {
            all_static,
            trend,
            statically,
            faster,
            regime,
            cause,
        } => {
            let mut t = format!(
                "{} the error changes by {} from {:.0} to {:.0} rpm",
                if *all_static { "statically" } else { "at fixed J" },
                pct(trend.change),
                trend.lo,
                trend.hi
            );
            if let Some(st) = statically {
                t.push_str(&format!(
                    " (statically by {} from {:.0} to {:.0} rpm)",
                    pct(st.change),
                    st.lo,
                    st.hi
                ));
            }
            let only = match regime {
                Regime::Both => "",
                Regime::ForwardOnly => " in forward flight, not statically",
                Regime::StaticOnly => " statically, not in forward flight",
            };
            t.push_str(&format!(
                ": the measured {name} grows {} with RPM than the model's{only}",
                if *faster { "faster" } else { "slower" }
            ));
            if *cause {
                t.push_str(rpm_cause(*regime));
            }
            t
        }
        Shows::RpmGroups {
            growing,
            low,
            high,
            confounded,
            power,
        } => {
            let mut t = format!(
                "{} ({} at {:.0} rpm, {} at {:.0} rpm",
                if *growing {
                    "growing with RPM"
                } else {
                    "largest at low RPM"
                },
                pct(low.error),
                low.rpm,
                pct(high.error),
                high.rpm
            );
            if *confounded {
                t.push_str(&format!(
                    "; at mean J {:.2} and {:.2}: RPM and J are not told apart",
                    low.j, high.j
                ));
            } else if let Some(n) = power {
                t.push_str(&format!(", about RPM^{n:.0}"));
            }
            t.push(')');
            t
        }
        Shows::ThrustTorque {
            relation,
            thrust,
            torque,
        } => format!(
            "Thrust and torque are off {} ({} and {} on average)",
            physics(*relation),
            pct(*thrust),
            pct(*torque)
        ),
    }
}

/// An effect list in words: the words before the effects that can make it, those effects, and
/// the words after them ("; not c, d", then the other quantity unaffected where it is).
pub struct EffectWords {
    /// The words before the effects that can make it (all of the sentence where none can).
    pub lead: String,
    /// The effects that can make it, best first.
    pub can: Vec<String>,
    /// The effects that cannot (said only beside some that can).
    pub cannot: Vec<String>,
}

impl EffectWords {
    /// The words of a list.
    pub fn of(e: &EffectList) -> EffectWords {
        let object = &e.object;
        if e.as_for_thrust {
            return EffectWords {
                lead: "The effects named for thrust can make it".into(),
                can: Vec::new(),
                cannot: Vec::new(),
            };
        }
        if e.can.is_empty() {
            return EffectWords {
                lead: format!(
                    "No candidate effect can make {object} within its bounds (from the model's response to each)"
                ),
                can: Vec::new(),
                cannot: Vec::new(),
            };
        }
        EffectWords {
            lead: format!("Effects that can make {object} (from the model's response to each, within its bounds): "),
            can: e.can.clone(),
            cannot: e.cannot.clone(),
        }
    }

    /// The list as a sentence, `tail` after it.
    pub fn sentence(&self, tail: &str) -> String {
        let not = if self.cannot.is_empty() {
            String::new()
        } else {
            format!("; not {}", self.cannot.join(", "))
        };
        format!("{}{}{not}{tail}", self.lead, self.can.join(", "))
    }
}

/// The other quantity unaffected, as the words after a part ("; thrust unaffected: ...").
pub fn unaffected_words(u: &Unaffected) -> String {
    let which = match &u.alone {
        None => String::new(),
        Some(a) if a.is_empty() => " (no candidate does, in the model within its bounds)".to_string(),
        Some(a) => format!(
            " ({} can, from the model's response to each within its bounds)",
            a.join(", ")
        ),
    };
    format!(
        "; {} unaffected: what moves {} alone{which}, not what changes the angles, the air or the RPM, which \
         move both",
        u.kept, u.moved
    )
}

/// A part in words: its sentence (capitalised after the first part), and its effects'
/// sentence where it names some, the other quantity unaffected after the last of them.
pub fn part_words(s: &Signature, index: usize, p: &Part) -> (String, Option<String>) {
    let mut text = part_sentence(s, &p.shows);
    if index > 0 {
        text = capitalised(&text);
    }
    let tail = p.unaffected.as_ref().map(unaffected_words).unwrap_or_default();
    match &p.effects {
        Some(e) => (text, Some(EffectWords::of(e).sentence(&tail))),
        None => (text + &tail, None),
    }
}

/// The pattern in words: each part's sentence, then its effects', joined by full stops.
pub fn signature_text(s: &Signature) -> String {
    s.parts
        .iter()
        .enumerate()
        .flat_map(|(i, p)| {
            let (text, effects) = part_words(s, i, p);
            std::iter::once(text).chain(effects)
        })
        .collect::<Vec<String>>()
        .join(". ")
}
