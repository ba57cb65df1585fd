//! The [`Engine`]: the d-independent part of the contact integrals for one spectrum (grids and
//! graded regions per refinement level, shared with its siblings), the kernel table of the
//! material pair, and the refinement loop around one evaluation ([`super::evaluate`]).

use super::evaluate::{Point, Scratch, evaluate_on, evaluate_sharing, g_sum_shared};
use super::graded::Graded;
use super::grid::{Grid, Knots};
use super::kernels::{Kernels, Mix};
use super::{Contact, MAX_REFINE, Request};
use crate::error::Error;
use crate::layer::stack::StackCache;
use crate::layer::tangential::TANGENTIAL_RTOL;
use crate::layer::{Bilayer, KernelTable, Stack, TangentialTable};
use crate::prec::{EPS, Estimate, INTERFACE_ATOL, KERNEL_RTOL, Settings, Termination};
use crate::psd::Spectrum;
use std::cell::RefCell;
use std::sync::{Arc, Mutex, OnceLock};

thread_local! {
    /// The evaluation's buffers, one set per thread, lent to one evaluation at a time.
    static SCRATCH: RefCell<Scratch> = RefCell::default();
}

/// The d-independent part of the contact integrals for one spectrum; serves every thickness.
pub struct Engine {
    spectrum: Spectrum,
    settings: Settings,
    grids: [OnceLock<Arc<Grid>>; MAX_REFINE + 1],
    graded: [OnceLock<Graded>; MAX_REFINE + 1],
    shared: Arc<Shared>,
}

/// What engines of one spectrum share ([`Engine::sibling`]).
#[derive(Default)]
struct Shared {
    /// Grids built so far, by their knot splits.
    grids: Mutex<Vec<(Vec<u32>, Arc<Grid>)>>,
    /// The kernel table of the last material pair evaluated (d-independent; rebuilt, wider, when
    /// a thickness needs q·d outside it).
    table: Mutex<Option<Arc<KernelTable>>>,
    /// The friction kernels' table covering the pair and range of `table` (sliding only), with
    /// the pair and the range of the static table it was last asked for (`None` when the
    /// kernels were not resolved there: not tried again for that range).
    tangential: Mutex<Option<TangentialEntry>>,
    /// The kernels of the last layer stack evaluated, per node (`contact::stack`).
    stack: Mutex<Option<StackCache>>,
}

/// A cached friction-kernel table: the pair, the static table's range, the table.
type TangentialEntry = (Bilayer, (f64, f64), Option<Arc<TangentialTable>>);

/// How far (in ln(qd)) a rebuilt kernel table reaches beyond the range asked for, so that a
/// thickness scan does not rebuild it at every step.
const TABLE_MARGIN: f64 = 2.0;

/// Panel width (in ln q) for a relative tolerance: the two-node rule's relative error per panel
/// is about h⁴ ψ⁗/(4320 ψ), with |ψ⁗/ψ| up to ~6⁴ where S⁻² ∝ (qd)⁻⁶.
pub fn panel_width(rtol: f64) -> f64 {
    (1.25 * rtol.max(1e-14).powf(0.25)).min(0.5)
}

impl Engine {
    pub fn new(spectrum: &Spectrum, settings: Settings) -> Self {
        Self {
            spectrum: spectrum.clone(),
            settings,
            grids: Default::default(),
            graded: Default::default(),
            shared: Arc::default(),
        }
    }

    /// An engine for the same spectrum with other settings, sharing this one's grids (where its
    /// panel width splits the knot intervals alike, as on a spectrum with dense points) and
    /// kernel tables: a check's search engine at a looser rtol costs no second set-up.
    pub fn sibling(&self, settings: Settings) -> Self {
        Self {
            spectrum: self.spectrum.clone(),
            settings,
            grids: Default::default(),
            graded: Default::default(),
            shared: Arc::clone(&self.shared),
        }
    }

    /// Builds the kernel table for `layers` at every thickness in [d_min, d_max] now, so that
    /// evaluations there (in parallel, in any order) all use the same one: a table rebuilt
    /// wider has other panels, and kernel values that differ within its 2e-14 tolerance.
    pub fn prepare(&self, layers: &Bilayer, d_min: f64, d_max: f64) {
        if d_min > 0.0 && d_max.is_finite() {
            self.table_covering(layers, d_min, d_max);
        }
    }

    /// The friction kernels' table covering the pair and range of the static `table`: the
    /// cached one, extended where the static table has grown ([`TangentialTable::extended`]:
    /// the panels it has are kept, so every thickness the static table serves sees the same
    /// friction kernels), or newly built.
    fn tangential_for(&self, table: &KernelTable) -> Option<Arc<TangentialTable>> {
        let mut cache = self
            .shared
            .tangential
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        let (layers, range) = (*table.layers(), table.range());
        let built = match cache.as_ref().filter(|(l, _, _)| *l == layers) {
            Some((_, r, None)) if *r == range => return None,
            Some((_, _, Some(t))) if t.covers(range.0, range.1) => return Some(Arc::clone(t)),
            Some((_, _, Some(t))) => t.extended(range.0, range.1),
            _ => TangentialTable::new(layers, range.0, range.1),
        }
        .map(Arc::new);
        *cache = Some((layers, range, built.clone()));
        built
    }

    /// A kernel table for `stack` covering every node's q·d, from the cache or newly built.
    fn table_for(&self, stack: &Stack) -> Option<Arc<KernelTable>> {
        self.table_covering(&stack.layers, stack.thickness, stack.thickness)
    }

    /// A kernel table for `layers` covering every node's q·d for d in [d_min, d_max].
    fn table_covering(&self, layers: &Bilayer, d_min: f64, d_max: f64) -> Option<Arc<KernelTable>> {
        let (q_lo, q_hi) = (self.spectrum.q_low(), self.spectrum.support().1);
        let (x_min, x_max) = (q_lo * d_min, q_hi * d_max);
        let mut cache = self.shared.table.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = cache
            .as_ref()
            .filter(|t| t.layers() == layers && t.covers(x_min, x_max))
        {
            return Some(Arc::clone(t));
        }
        let (mut lo, mut hi) = (x_min.ln() - TABLE_MARGIN, x_max.ln() + TABLE_MARGIN);
        if let Some(t) = cache.as_ref().filter(|t| t.layers() == layers) {
            let (a, b) = t.range();
            (lo, hi) = (lo.min(a.ln()), hi.max(b.ln()));
        }
        let table = Arc::new(KernelTable::new(*layers, lo.exp(), hi.exp())?);
        *cache = Some(Arc::clone(&table));
        Some(table)
    }

    /// The stack cache of this engine and its siblings (taken out while an evaluation uses it).
    pub(super) fn stack_cache(&self) -> &Mutex<Option<StackCache>> {
        &self.shared.stack
    }

    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }

    pub fn settings(&self) -> Settings {
        self.settings
    }

    fn grid(&self, level: usize) -> Result<&Grid, Error> {
        if let Some(g) = self.grids[level].get() {
            return Ok(g);
        }
        let knots = Knots::new(
            &self.spectrum,
            panel_width(self.settings.rtol) / (1 << level) as f64,
        )?;
        Ok(self.grids[level].get_or_init(|| {
            let mut grids = self.shared.grids.lock().unwrap_or_else(|e| e.into_inner());
            if let Some((_, g)) = grids.iter().find(|(s, _)| *s == knots.splits) {
                return Arc::clone(g);
            }
            let g = Arc::new(Grid::new(&self.spectrum, &knots));
            grids.push((knots.splits, Arc::clone(&g)));
            g
        }))
    }

    fn graded(&self, level: usize) -> Result<&Graded, Error> {
        let grid = self.grid(level)?;
        Ok(self.graded[level].get_or_init(|| {
            Graded::new(
                &self.spectrum,
                grid,
                panel_width(self.settings.rtol) / (1 << level) as f64,
                // Each level halves the base panels: their error falls 16-fold.
                self.settings.rtol / 16f64.powi(level as i32),
            )
        }))
    }

    /// Evaluate at one stack (thickness) and nominal pressure p0 (Pa).
    pub fn evaluate(&self, stack: &Stack, p0: f64, request: Request) -> Result<Contact, Error> {
        Ok(self.evaluate_mixed(stack, p0, request, Mix::Static)?.0)
    }

    /// [`Self::evaluate`] with the interface integrals' kernels chosen by `mix` (its σ and τ
    /// slots are returned as `sigma_rms_interface` and `tau_rms_interface`), and under
    /// [`Mix::Sliding`] with τ requested the friction slots' rms ([`Self::refine`]).
    pub(super) fn evaluate_mixed(
        &self,
        stack: &Stack,
        p0: f64,
        request: Request,
        mix: Mix,
    ) -> Result<(Contact, Option<[Estimate; 2]>), Error> {
        if !(p0.is_finite() && p0 > 0.0) {
            return Err(Error::invalid(
                "nominal pressure p0",
                p0,
                "a finite pressure > 0 in Pa",
            ));
        }
        let table = self.table_for(stack);
        let tangential = match (mix, table.as_deref()) {
            (Mix::Static, _) | (_, None) => None,
            (_, Some(t)) => self.tangential_for(t),
        };
        let kernels = Kernels::new(
            table.as_deref(),
            &stack.layers,
            stack.thickness,
            self.spectrum.q_low(),
        )
        .mixed(mix, tangential.as_deref());
        let kernel_rtol = match mix {
            Mix::Static => KERNEL_RTOL,
            _ => KERNEL_RTOL.max(TANGENTIAL_RTOL),
        };
        let at = At {
            depth: stack.thickness,
            e_top: stack.layers.film.e_star(),
            p0,
            kernel_rtol,
        };
        self.refine(&kernels, at, request)
    }

    /// The evaluation with `kernels`, on grids refined until the estimates meet rtol (at most
    /// [`MAX_REFINE`] times). Under [`Mix::Sliding`] with τ requested, also the friction slots'
    /// rms (along x, along y), evaluated with the others (the same G, P and nodes): each of the
    /// two groups, the requested quantities and the friction slots with G1 and A, is taken from
    /// the first grid on which it meets rtol, and only a group that has not is evaluated on the
    /// next. The kernel evaluations counted are those of every grid evaluated.
    fn refine(&self, kernels: &Kernels, at: At, request: Request) -> Result<Refined, Error> {
        let mut r = Refinement::new(kernels, request);
        for level in 0..=MAX_REFINE {
            SCRATCH.with_borrow_mut(|s| r.step(self, level, (kernels, at, request), None, s))?;
            if r.done() {
                break;
            }
        }
        Ok(r.finish(self.settings.rtol))
    }

    /// [`Self::refine`] of several evaluations whose kernels share S⁻² (a stack's interfaces,
    /// each with its kernels, where and what): grid by grid, G's sum formed once per grid for
    /// all of them. Each is refined exactly as by [`Self::refine`] alone (the same grids, the
    /// same sums to the last bit), until every one has met rtol.
    pub(super) fn refine_sharing(
        &self,
        each: &[(Kernels, At, Request)],
    ) -> Result<Vec<Refined>, Error> {
        let mut all: Vec<Refinement> = each
            .iter()
            .map(|(kernels, _, request)| Refinement::new(kernels, *request))
            .collect();
        for level in 0..=MAX_REFINE {
            let Some(first) = all.iter().position(|r| !r.done()) else {
                break;
            };
            SCRATCH.with_borrow_mut(|s| {
                let (kernels, at, _) = &each[first];
                let sums = all[first].g_sum(self, level, kernels, *at, s)?;
                for (r, &(ref kernels, at, request)) in all.iter_mut().zip(each) {
                    if !r.done() {
                        r.step(self, level, (kernels, at, request), Some(sums), s)?;
                    }
                }
                Ok::<_, Error>(())
            })?;
        }
        let rtol = self.settings.rtol;
        Ok(all.into_iter().map(|r| r.finish(rtol)).collect())
    }
}

/// A refined evaluation: the contact, and the friction slots' rms when asked for
/// ([`Engine::refine`]).
type Refined = (Contact, Option<[Estimate; 2]>);

/// One evaluation's refinement over the grid levels ([`Engine::refine`]): the kernel
/// evaluations so far, and each group (the requested quantities; the friction slots, when
/// asked for) as evaluated on the last grid and whether it has met rtol.
struct Refinement {
    evaluations: usize,
    interface: usize,
    main: Option<Contact>,
    slots: Option<Contact>,
    main_done: bool,
    slots_done: bool,
}

impl Refinement {
    fn new(kernels: &Kernels, request: Request) -> Self {
        let friction = kernels.sliding() && request.tau_interface;
        Self {
            evaluations: 0,
            interface: 0,
            main: None,
            slots: None,
            main_done: false,
            slots_done: !friction,
        }
    }

    fn done(&self) -> bool {
        self.main_done && self.slots_done
    }

    /// The evaluation point on the grid of `level` (its graded region only when an interface
    /// quantity or the friction slots are still wanted).
    fn point<'a>(
        &self,
        engine: &'a Engine,
        level: usize,
        (kernels, at, request): (&'a Kernels<'a>, At, Request),
    ) -> Result<Point<'a>, Error> {
        let grid = engine.grid(level)?;
        let req = if self.main_done {
            Request::default()
        } else {
            request
        };
        let graded = match req.interface() || !self.slots_done {
            true => Some(engine.graded(level)?),
            false => None,
        };
        Ok(Point {
            grid,
            graded,
            kernels,
            depth: at.depth,
            e_top: at.e_top,
            p0: at.p0,
            req,
            friction: !self.slots_done,
            rtol: engine.settings.rtol,
        })
    }

    /// G's sum on the grid of `level` with `kernels`' S⁻², into `s` ([`g_sum_shared`]).
    fn g_sum(
        &self,
        engine: &Engine,
        level: usize,
        kernels: &Kernels,
        at: At,
        s: &mut Scratch,
    ) -> Result<(f64, f64), Error> {
        let point = self.point(engine, level, (kernels, at, Request::default()))?;
        g_sum_shared(&point, s)
    }

    /// The evaluation on the grid of `level` of the groups not yet done, with G's sum `shared`
    /// if it is in `s` already.
    fn step(
        &mut self,
        engine: &Engine,
        level: usize,
        what: (&Kernels, At, Request),
        shared: Option<(f64, f64)>,
        s: &mut Scratch,
    ) -> Result<(), Error> {
        let rtol = engine.settings.rtol;
        let floor = rounding_floor(what.1.kernel_rtol);
        let point = self.point(engine, level, what)?;
        self.evaluations += point.grid.q.len();
        let (mut c, pair) = match shared {
            Some(sums) => evaluate_sharing(&point, self.evaluations, sums, s)?,
            None => evaluate_on(&point, self.evaluations, s)?,
        };
        self.interface += c.interface_kernel_evaluations;
        self.evaluations = c.kernel_evaluations;
        if let Some([fx, fy]) = pair {
            // The friction slots as a contact of their own, in the σ and τ slots.
            let mut f = Contact {
                sigma_rms_top: None,
                e_eff_over_e_film: None,
                sigma_rms_interface: Some(fx),
                tau_rms_interface: Some(fy),
                ..c.clone()
            };
            add_rounding_floor(&mut f, floor);
            self.slots_done = converged(&f, rtol);
            self.slots = Some(f);
        }
        if !self.main_done {
            add_rounding_floor(&mut c, floor);
            self.main_done = converged(&c, rtol);
            self.main = Some(c);
        }
        Ok(())
    }

    /// The contact (and the friction slots' rms), marked where rtol was not met.
    fn finish(self, rtol: f64) -> Refined {
        let mut c = self.main.expect("at least one grid level");
        c.kernel_evaluations = self.evaluations;
        c.interface_kernel_evaluations = self.interface;
        let pair = self.slots.map(|mut f| {
            if !converged(&f, rtol) {
                mark_not_reached(&mut f, rtol);
            }
            let slot = |e: Option<Estimate>| e.expect("both friction slots");
            [slot(f.sigma_rms_interface), slot(f.tau_rms_interface)]
        });
        if !converged(&c, rtol) {
            mark_not_reached(&mut c, rtol);
        }
        (c, pair)
    }
}

/// Where one evaluation is made: the interface's depth (m), the top layer's E* (Pa), the
/// nominal pressure p0 (Pa), and the kernels' relative error bound.
#[derive(Debug, Clone, Copy)]
pub(super) struct At {
    pub(super) depth: f64,
    pub(super) e_top: f64,
    pub(super) p0: f64,
    pub(super) kernel_rtol: f64,
}

fn converged(c: &Contact, rtol: f64) -> bool {
    let [g1, area, top, e_eff, sigma, tau] = [
        Some(&c.g1),
        Some(&c.area_fraction),
        c.sigma_rms_top.as_ref(),
        c.e_eff_over_e_film.as_ref(),
        c.sigma_rms_interface.as_ref(),
        c.tau_rms_interface.as_ref(),
    ];
    [g1, area, top, e_eff]
        .into_iter()
        .flatten()
        .all(|e| within(e, rtol, 0.0))
        && [sigma, tau]
            .into_iter()
            .flatten()
            .all(|e| within(e, rtol, INTERFACE_ATOL))
}

/// Whether an estimate's error is within rtol of its value plus an absolute `atol` (a NaN error
/// never is).
fn within(e: &Estimate, rtol: f64, atol: f64) -> bool {
    e.err <= rtol * e.value.abs() + atol
}

/// Relative error every contact result carries whatever the grid: the kernels' rounding
/// ([`KERNEL_RTOL`], entering through S⁻² and f², g², i.e. twice, and once more through the
/// σ–G relations) and the summation over some thousand nodes (64 ε). The quadrature estimate
/// does not see these.
pub const ROUNDING_FLOOR: f64 = rounding_floor(KERNEL_RTOL);

/// [`ROUNDING_FLOOR`] for kernels with relative error bound `kernel_rtol`.
pub const fn rounding_floor(kernel_rtol: f64) -> f64 {
    4.0 * kernel_rtol + 64.0 * EPS
}

fn add_rounding_floor(c: &mut Contact, floor: f64) {
    for e in estimates_mut(c) {
        e.err += floor * e.value.abs();
    }
}

fn estimates_mut(c: &mut Contact) -> impl Iterator<Item = &mut Estimate> {
    [
        Some(&mut c.g1),
        Some(&mut c.area_fraction),
        c.sigma_rms_top.as_mut(),
        c.sigma_rms_interface.as_mut(),
        c.tau_rms_interface.as_mut(),
        c.e_eff_over_e_film.as_mut(),
    ]
    .into_iter()
    .flatten()
}

fn mark_not_reached(c: &mut Contact, rtol: f64) {
    let mark = |e: &mut Estimate, atol: f64| {
        if !within(e, rtol, atol) {
            e.status = Termination::ToleranceNotReached;
        }
    };
    for e in [
        Some(&mut c.g1),
        Some(&mut c.area_fraction),
        c.sigma_rms_top.as_mut(),
        c.e_eff_over_e_film.as_mut(),
    ]
    .into_iter()
    .flatten()
    {
        mark(e, 0.0);
    }
    for e in [c.sigma_rms_interface.as_mut(), c.tau_rms_interface.as_mut()]
        .into_iter()
        .flatten()
    {
        mark(e, INTERFACE_ATOL);
    }
}
