//! Deciding, before any pass runs, what each pass does this frame: conditions, culling of
//! passes nobody needs, change detection through keys and input versions, amortisation.

use crate::io::Availability;
use crate::pass::Budget;
use crate::report::Reason;
use crate::scheduler::{Action, Scheduler};

impl<C> Scheduler<C> {
    pub(crate) fn plan(&mut self, ctx: &C) {
        let n = self.meta.len();
        // 1. Conditions.
        for i in 0..n {
            match self.meta[i].conditions.iter().find(|(_, c)| !c(ctx)) {
                Some((label, _)) => {
                    self.actions[i] = Action::Skip;
                    self.reasons[i] = Reason::ConditionFalse { condition: label.clone() };
                }
                None => self.actions[i] = Action::Run,
            }
        }
        // 2. Culling, from the outputs backwards: a pass is needed when it has a side effect,
        //    writes a graph output, or feeds a needed pass.
        let sh = &self.shared;
        for &p in sh.topo.order.iter().rev() {
            let i = p as usize;
            if self.actions[i] == Action::Skip {
                continue;
            }
            let needed = self.meta[i].side_effect
                || sh.writes[i].iter().any(|&r| sh.outputs[r as usize])
                || sh.topo.consumers[i].iter().any(|&c| self.actions[c as usize] != Action::Skip);
            if !needed {
                self.actions[i] = Action::Skip;
                self.reasons[i] = Reason::NoReader;
            }
        }
        // 3. Change detection and amortisation, in order, so that a pass sees whether its
        //    producers rewrite its inputs this frame.
        for &p in &sh.topo.order {
            let i = p as usize;
            if self.actions[i] == Action::Skip {
                continue;
            }
            let meta = &mut self.meta[i];
            let st = &mut self.state[i];
            let mut changed_key = None;
            for (k, key) in meta.keys.iter_mut().enumerate() {
                if key.changed(ctx) && changed_key.is_none() {
                    changed_key = Some(k);
                }
            }
            let reads = &sh.reads[i];
            let actions = &self.actions;
            let skipped_now = |r: u32| {
                sh.topo.producer[r as usize].is_some_and(|p| actions[p as usize] == Action::Skip)
            };
            let changed_input = reads
                .iter()
                .zip(st.input_versions.iter().zip(&st.input_skipped))
                .find(|&(&r, (&v, &s))| self.versions[r as usize] != v || skipped_now(r) != s)
                .map(|(&r, _)| r);
            let cause = if st.invalidated {
                Some(Reason::Invalidated)
            } else if !st.ran_once {
                Some(Reason::FirstRun)
            } else if let Some(k) = changed_key {
                Some(Reason::KeyChanged { key: meta.keys[k].label().to_owned() })
            } else {
                changed_input.map(|r| Reason::InputChanged {
                    resource: sh.resource_names[r as usize].clone(),
                })
            };
            let (action, reason, restart) = match meta.amortise {
                None if !meta.cached => (Action::Run, Reason::EveryFrame, true),
                None => match cause {
                    Some(c) => (Action::Run, c, true),
                    None => (Action::Reuse, Reason::Unchanged, false),
                },
                Some(a) => {
                    let midway = st.done > 0 && st.done < a.units;
                    let (reason, restart) = match cause {
                        Some(c @ (Reason::Invalidated | Reason::FirstRun)) => {
                            (if midway { restarted(c) } else { c }, true)
                        }
                        Some(c) if meta.cached => (if midway { restarted(c) } else { c }, true),
                        _ if meta.cached && st.done >= a.units => (Reason::Unchanged, false),
                        _ if st.done >= a.units => (Reason::NextCycle, true),
                        _ => (Reason::Continuing, false),
                    };
                    if restart {
                        st.done = 0;
                    }
                    if meta.cached && st.done >= a.units {
                        (Action::Reuse, reason, false)
                    } else {
                        let remaining = a.units - st.done;
                        let (max, budget_ms) = match a.budget {
                            Budget::Units(k) => (k.min(remaining), None),
                            Budget::Millis(ms) => (remaining, Some(ms)),
                        };
                        let act =
                            Action::Amortise { start: st.done, max, total: a.units, budget_ms };
                        (act, reason, restart)
                    }
                }
            };
            if restart {
                for key in meta.keys.iter_mut() {
                    key.commit();
                }
                for (v, &r) in st.input_versions.iter_mut().zip(reads) {
                    *v = self.versions[r as usize];
                }
                for (s, &r) in st.input_skipped.iter_mut().zip(reads) {
                    *s = skipped_now(r);
                }
                st.ran_once = true;
                st.invalidated = false;
            }
            if action.executes() {
                for &w in &sh.writes[i] {
                    self.versions[w as usize] += 1;
                }
            }
            self.actions[i] = action;
            self.reasons[i] = reason;
        }
        // 4. What readers will find.
        for r in 0..self.availability.len() {
            self.availability[r] = match sh.topo.producer[r] {
                Some(p) if self.actions[p as usize] == Action::Skip => {
                    Availability::ProducerSkipped(p)
                }
                Some(_) => Availability::Active,
                None if self.input_set[r] => Availability::Active,
                None => Availability::InputUnset,
            };
        }
    }
}

fn restarted(cause: Reason) -> Reason {
    Reason::Restarted { because: Box::new(cause) }
}
