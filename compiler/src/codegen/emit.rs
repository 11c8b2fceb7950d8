//! The program and its DMs as Rust items: `Program` and its
//! `DmProgram`/`App` impls, the entry points (`program()`, `run`, `main`),
//! and one module per DM (its situation table and templates, instance builders, dispatch).
//! The per-situation code is [`super::step`]'s (on terms) and
//! [`super::native`]'s (on Rust values).
//!
//! What one function of the program says for every DM is not repeated per
//! DM: `run_situation` enters an all-native DM's frame (its `nat_entry`,
//! no `run_situation` or `run_native` of its own), `fresh_head` makes a
//! head that is an atom or of distinct variables (a DM's own `head` only
//! for another), `locals` (a DM's own function only when it has locals),
//! `dm_by_name`; the runtime's `machine::nat_hand_over` serves a DM without
//! locals, and its `machine::nat_drive` runs the native stack
//! over the program's `NatFrame`. Invariant: the program's dispatch names only the
//! per-DM functions a DM's module has (`DmItems` says which).

use super::*;

impl Gen<'_> {
    pub(super) fn emit(&self, ir: &Ir, source: &str) -> TokenStream {
        let rt = quote!(::sitlog_runtime);
        let prolog_names: Vec<Literal> = ir
            .prolog_sources
            .iter()
            .map(|f| Literal::string(&f.name))
            .collect();
        let prolog_texts: Vec<Literal> = ir
            .prolog_sources
            .iter()
            .map(|f| Literal::string(&f.text))
            .collect();

        let places = super::places::places(ir);
        // DM modules.
        let mut dm_namer = Namer::default();
        let mut modules = Vec::new();
        let mut dm_rows = Vec::new();
        let mut dm_mods = Vec::new();
        // The DMs with instance builders (a template whose text does not
        // read back): their own `instantiate`.
        let mut builder_arms = Vec::new();
        // The DMs with compiled situations that have no template: their
        // own `select_compiled`.
        let mut select_dm_arms = Vec::new();
        let mut run_arms = Vec::new();
        let mut any_all_native = false;
        let mut term_arms = Vec::new();
        let mut locals_arms = Vec::new();
        let mut head_arms = Vec::new();
        let mut exit_dm_arms = Vec::new();
        for (i, dm) in ir.dms.iter().enumerate() {
            let m = ident(&dm_namer.fresh(format!("dm_{}", snake(dm.name.as_str()))));
            dm_mods.push(m.clone());
            let items = self.emit_dm(dm, i, &m);
            modules.push(items.module);
            dm_rows.push(items.row);
            let ix = Literal::u32_unsuffixed(i as u32);
            if items.builders {
                builder_arms.push(quote!(#ix => #m::instantiate(self, sit, store),));
            }
            if items.selects {
                select_dm_arms.push(quote!(#ix => #m::select_compiled(self, sit, value, store),));
            }
            if items.all_native {
                // Every situation natively (its frame entered), else
                // from its template.
                let d = format_ident!("D{}", i);
                any_all_native = true;
                run_arms.push(quote!(#ix => #m::nat_entry(self, cx, sit).map(NatFrame::#d),));
            } else {
                run_arms.push(quote!(#ix => return #m::run_situation(self, sit, cx),));
                term_arms.push(quote!(#ix => #m::run_situation(self, sit, cx),));
            }
            // A head the table does not make: the DM's `head`.
            if items.head.is_none() {
                head_arms.push(quote!(#ix => #m::head(self, store),));
            }
            if !dm.locals.is_empty() {
                locals_arms.push(quote!(#ix => #m::locals(self, store),));
            }
            if items.exits {
                exit_dm_arms.push(quote!(#ix => #m::run_exit(self, sit, saved, final_id, cx),));
            }
        }
        let native_driver = self.native_driver(ir, &dm_mods, &modules);
        let plain_rs = self.plain_rs_module();
        // A DM with every situation native: its frame entered here and run
        // by the native driver (`Step::Template`: a value did not convert).
        let run_body = if any_all_native {
            quote! {
                let frame = match dm {
                    #(#run_arms)*
                    _ => return Err(cx.error("no such DM", None)),
                };
                match frame {
                    Some(frame) => {
                        let run = cx.typed_run();
                        machine::nat_drive(self, cx, frame, &run)
                    }
                    None => Ok(Step::Template),
                }
            }
        } else {
            quote! {
                match dm {
                    #(#term_arms)*
                    _ => Err(cx.error("no such DM", None)),
                }
            }
        };
        // Constants: their `writeq` texts, read once by `Program::new`; a
        // constant whose text does not read back as itself is built by
        // code after them (its text `[]`).
        let empty = HashMap::new();
        let mut const_texts = Vec::new();
        let mut const_fixups = Vec::new();
        for (i, (text, t)) in self.consts.iter().enumerate() {
            if let Some(lit) = self.const_text(*t, text) {
                const_texts.push(lit);
                continue;
            }
            const_texts.push(quote!("[]"));
            let ix = Literal::usize_unsuffixed(i);
            let mut next_tmp = 0;
            let b = self.build(*t, &empty, true, &mut next_tmp);
            let stmts = b.stmts.iter().map(|(t, e)| quote!(let #t = #e;));
            let value = b.value;
            const_fixups.push(quote!(k[#ix] = { #(#stmts)* #value };));
        }
        // The patterns native code fills (`native::fill`), registered while
        // the DMs' code was made: they read back.
        for text in self.patterns.borrow().iter() {
            const_texts.push(wrapped_literal(text, 88).parse().expect("a string literal"));
        }
        // The dispatches to the DMs that have their own function (none:
        // the generic case alone).
        let instantiate_body = if builder_arms.is_empty() {
            quote!(self.instance(dm, sit, store))
        } else {
            quote!(match dm {
                #(#builder_arms)*
                _ => self.instance(dm, sit, store),
            })
        };
        let select_rest = if select_dm_arms.is_empty() {
            quote!(true)
        } else {
            quote!(match dm {
                #(#select_dm_arms)*
                _ => true,
            })
        };
        // The heads the table does not make (`DmRow::head` `None`).
        // Only a program whose plans lowered the runtime's `when/3` says
        // so (the machine checks the registry at the run's start).
        let runtime_when = self.mir.runtime_when.then(|| {
            quote! {
                fn lowers_runtime_when(&self) -> bool {
                    true
                }
            }
        });
        let head_rest = if head_arms.is_empty() {
            quote!(panic!("no DM number {dm}"))
        } else {
            quote!(match dm {
                #(#head_arms)*
                _ => panic!("no DM number {dm}"),
            })
        };
        let run_exit_body = if exit_dm_arms.is_empty() {
            quote!(Err(cx.error("the situation has no compiled code", None)))
        } else {
            quote!(match dm {
                #(#exit_dm_arms)*
                _ => Err(cx.error("the situation has no compiled code", None)),
            })
        };
        let dm_count = Literal::usize_unsuffixed(ir.dms.len());

        // Globals.
        let global_names: Vec<Ident> = (0..ir.globals.len())
            .map(|i| format_ident!("g{}", i))
            .collect();
        let mut global_stmts = Vec::new();
        let mut global_entries = Vec::new();
        for ((n, v), gname) in ir.globals.iter().zip(&global_names) {
            let e = self.builder_expr(*v);
            let a = &self.atoms[self.atom_ix[n]].1;
            global_stmts.push(quote!(let #gname = #e;));
            global_entries.push(quote!((p.atoms.#a, #gname)));
        }
        let globals_body = quote!(#(#global_stmts)*);
        let globals_prelude = Self::prelude(&globals_body);
        let basic_actions = ir.basic_actions.iter().map(|b| {
            let a = &self.atoms[self.atom_ix[b]].1;
            quote!(self.atoms.#a)
        });
        let recovery: Vec<TokenStream> = ir
            .recovery
            .iter()
            .map(|(ty, dm)| {
                let t = &self.atoms[self.atom_ix[ty]].1;
                let d = &self.atoms[self.atom_ix[dm]].1;
                quote!((self.atoms.#t, self.atoms.#d))
            })
            .collect();
        let source_doc = format!(" The SitLog program `{source}`, compiled by sitlog-compiler.");
        // Only the constants the code names, renumbered in order (a
        // constant of the program that is only part of a pattern is not).
        let mut used = std::collections::BTreeSet::new();
        for ts in modules
            .iter()
            .chain([&native_driver, &globals_body])
            .chain(&const_fixups)
        {
            const_uses(ts, &mut used);
        }
        let renumbered: HashMap<usize, usize> = used
            .iter()
            .enumerate()
            .map(|(new, &old)| (old, new))
            .collect();
        let const_texts: Vec<TokenStream> = const_texts
            .into_iter()
            .enumerate()
            .filter(|(i, _)| used.contains(i))
            .map(|(_, t)| t)
            .collect();
        let renumber = |ts: &TokenStream| renumber_consts(ts.clone(), &renumbered);
        let modules: Vec<TokenStream> = modules.iter().map(renumber).collect();
        let native_driver = renumber(&native_driver);
        let globals_body = renumber(&globals_body);
        let const_fixups: Vec<TokenStream> = const_fixups.iter().map(renumber).collect();
        let const_count = Literal::usize_unsuffixed(const_texts.len());
        let k_mut = (!const_fixups.is_empty()).then(|| quote!(mut));

        let body = quote! {
            #[doc = #source_doc]
            ///
            /// Runs on the runtime's DM machine (`sitlog_runtime::machine`), which
            /// implements every semantic step: situations with atom ids run as
            /// code calling those steps, the others as instances built here.
            ///
            /// Each DM is a module `dm_<name>` (its items documented here once):
            /// `SITUATIONS` (per situation its kind, id (name, arity), line and
            /// column, its in_arg's (`.in_arg(..)`), read by the runtime's `SitTable` with the DM's row of
            /// `DMS`), `TEMPLATES` (the situations' templates (D-7) as `writeq`
            /// text, read once into the program's store; `""` for a
            /// situation never instantiated from one), and for the situations
            /// with native code (see `sitlog_compiler::codegen::native`) `enum
            /// Nat` (one variant per situation, its fields the id's variables; a
            /// `W<n>` variant waits for the DM it called; a frame holds its
            /// first variant without fields (else `Moved`) while it runs; its
            /// `machine::NatAt`: `id_term`, its id
            /// filled from its pattern, and `waits`, the situation a `W<n>`
            /// waits in and the pipe value it keeps), `Frame` (the DM's frame on
            /// the native stack: parameters, locals, the `Nat` it is in; its
            /// call term is made by `NatFrame`'s dispatch), `nat_entry` (the
            /// frame entered at a situation, its values converted: `None` when
            /// one does not), `nat_step` (runs the frame on the program's native
            /// stack until it calls a DM (`call` set), ends in a final below the
            /// base, or hands over to the machine; never inlined: the driver's
            /// dispatch on `NatFrame` then only jumps to it and pays no other
            /// DM's prologue; a `W<n>` arm runs when the callee it waited for
            /// is given back, `ret`), `nat_hand_over` (a DM with locals: before
            /// the machine sees the state, the native frames below made machine
            /// frames by the runtime's `machine::nat_hand_over`, which serves
            /// the other DMs, then the locals written back), `nat_wait` (a DM
            /// with locals and waiting situations: a frame
            /// waiting for its callee made the machine's, the locals written
            /// back; for the others the runtime's `NatAt::nat_wait` from `waits`
            /// and `id_term`) and, in a DM with term code too, `run_native` (an
            /// all-native DM's frame is entered by `run_situation`). The native
            /// stack itself is the runtime's (`machine::nat_drive`), over the
            /// program's `NatFrame`.
            #[allow(dead_code, non_camel_case_types, unused_variables, clippy::all)]
            pub struct Program {
                /// Frozen store holding the constants; every run starts from a clone.
                store: Store,
                pub atoms: Atoms,
                /// The constants (`CONSTS`) in the frozen store.
                pub k: [Term; #const_count],
                /// The situations' templates in the frozen store, by DM and
                /// situation (each DM's `TEMPLATES`).
                templates: machine::Templates,
                /// The situations' kinds, ids and places (each DM's `SITUATIONS`).
                sits: SitTable,
            }

            /// The machine's context of this program's code.
            #[allow(dead_code)]
            pub type Ctx<'a, 'b> = Cx<'a, 'b, Program>;

            /// What native code's step gives: the machine's step when it hands
            /// over (`None`: it did not).
            #[allow(dead_code)]
            pub type NatResult = Result<Option<Step>, RunError>;

            /// The program's DMs in load order: each one's name, the file it
            /// is written in, its head's arity when the table makes its head
            /// (`DmRow`).
            pub const DMS: [DmRow; #dm_count] = [#(#dm_rows),*];

            /// Where each DM's arcs and constructs of L are written, read
            /// only for a run-time error's place (`machine::places`).
            pub const PLACES: [&str; #dm_count] = [#(#places),*];

            /// The program's ground compound terms (and big integers) as
            /// `writeq` text, read once by [`Program::new`]; code names
            /// constant `i` `k[i]`.
            pub const CONSTS: [&str; #const_count] = [#(#const_texts),*];

            #[allow(dead_code, unused_variables, clippy::all)]
            impl Program {
                /// Interns the atoms and reads the constants and templates.
                pub fn new() -> Program {
                    let mut store = Store::new();
                    let a = Atoms::new();
                    let store = &mut store;
                    let #k_mut k = machine::read_consts(store, &CONSTS);
                    #(#const_fixups)*
                    let (templates, sits) = machine::read_dms(
                        store,
                        &DMS,
                        &[#((&#dm_mods::SITUATIONS, &#dm_mods::TEMPLATES)),*],
                    );
                    let mut store = ::std::mem::take(store);
                    store.freeze();
                    Program { store, atoms: a, k, templates, sits: sits.with_places(&PLACES) }
                }

                /// A fresh instance of situation `sit` of DM `dm` from its
                /// template (`None`: it has none).
                pub fn instance(&self, dm: DmIx, sit: SitIx, store: &mut Store) -> Option<Instance> {
                    self.templates.instance(dm, sit, store)
                }

                /// The names of the declared basic actions (`basic_actions.pl`).
                pub fn basic_actions(&self) -> Vec<Atom> {
                    vec![#(#basic_actions),*]
                }

                /// A store for one run (a clone of the frozen one) and fresh
                /// initial values of the global variables.
                pub fn initial_state(&self) -> (Store, Vars) {
                    let p = self;
                    let mut store = self.store.clone();
                    let store = &mut store;
                    #globals_prelude
                    #globals_body
                    let globals = Vars::from_entries(vec![#(#global_entries),*]);
                    (::std::mem::take(store), globals)
                }
            }

            #[allow(clippy::all)]
            impl ::std::default::Default for Program {
                fn default() -> Program {
                    Program::new()
                }
            }

            #[allow(unused_variables, clippy::all)]
            impl machine::DmProgram for Program {
                fn dm_by_name(&self, name: Atom) -> Option<DmIx> {
                    // The first DM of the name in load order.
                    (0..#dm_count).find(|&dm| self.dm_name(dm) == name)
                }
                fn dm_name(&self, dm: DmIx) -> Atom {
                    self.sits.dm_name(dm)
                }
                #runtime_when
                fn situation_count(&self, dm: DmIx) -> usize {
                    self.sits.count(dm)
                }
                fn kind(&self, dm: DmIx, sit: SitIx) -> Kind {
                    self.sits.kind(dm, sit)
                }
                fn fresh_head(&self, dm: DmIx, store: &mut Store) -> Term {
                    match self.sits.fresh_head(dm, store) {
                        Some(head) => head,
                        None => #head_rest,
                    }
                }
                fn instantiate(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                    store: &mut Store,
                ) -> Option<Instance> {
                    #instantiate_body
                }
                fn may_select(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                    value: Term,
                    store: &Store,
                ) -> bool {
                    self.sits.may_select(dm, sit, store.functor(value))
                }
                fn locals(&self, dm: DmIx, store: &mut Store) -> Vars {
                    match dm {
                        #(#locals_arms)*
                        _ if dm < #dm_count => Vars::default(),
                        _ => panic!("no DM number {dm}"),
                    }
                }
                fn location(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                ) -> Option<String> {
                    Some(self.sits.location(dm, sit))
                }
                fn in_arg_location(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                ) -> Option<String> {
                    self.sits.in_arg_location(dm, sit)
                }
                fn compiled_id(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                ) -> Option<(Atom, usize)> {
                    self.sits.compiled_id(dm, sit)
                }
                fn select_compiled(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                    value: Term,
                    store: &mut Store,
                ) -> bool {
                    match self.templates.select(dm, sit, value, store) {
                        Some(taken) => taken,
                        None => #select_rest,
                    }
                }
                fn run_situation(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                    cx: &mut Cx<'_, '_, Self>,
                ) -> Result<Step, RunError> {
                    #run_body
                }
                fn run_exit(
                    &self,
                    dm: DmIx,
                    sit: SitIx,
                    saved: Term,
                    final_id: Term,
                    cx: &mut Cx<'_, '_, Self>,
                ) -> Result<Step, RunError> {
                    #run_exit_body
                }
            }

            #[allow(clippy::all)]
            impl #rt::app::App for Program {
                fn initial_state(&self) -> (Store, Vars) {
                    Program::initial_state(self)
                }
                fn basic_actions(&self) -> Vec<Atom> {
                    Program::basic_actions(self)
                }
                fn recovery(&self) -> Vec<(Atom, Atom)> {
                    vec![#(#recovery),*]
                }
                fn error_location(&self, error: &RunError) -> Option<String> {
                    self.sits.error_location(error)
                }
            }

            /// The program, built on first use.
            #[allow(dead_code)]
            pub fn program() -> &'static Program {
                static PROGRAM: ::std::sync::OnceLock<Program> = ::std::sync::OnceLock::new();
                PROGRAM.get_or_init(Program::new)
            }

            /// Runs the program in test mode from `main` (a DM call, as a term) with
            /// `in_arg` (a term; the atom `none` when absent): the runtime's
            /// [`run`](::sitlog_runtime::app::run) on this program.
            #[allow(dead_code)]
            pub fn run(
                main: &str,
                in_arg: Option<&str>,
                options: machine::Options,
                functions: #rt::Functions,
                perception: &mut dyn machine::Perception,
                actions: &mut dyn machine::Actions,
                observer: Option<&mut dyn machine::Observer>,
            ) -> Result<(machine::Outcome, Store), String> {
                #rt::app::run(program(), main, in_arg, options, functions, perception, actions, observer)
            }

            /// The application's Prolog sources (`templates.pl`, `user_functions.pl`), embedded.
            #[allow(dead_code)]
            pub const PROLOG_SOURCES: &[(&str, &str)] = &[#((#prolog_names, #prolog_texts)),*];

            /// The standard user functions plus the application's Prolog ones.
            #[allow(dead_code)]
            pub fn functions() -> Result<#rt::Functions, String> {
                let mut functions = #rt::Functions::standard();
                #rt::install_prolog_sources(&mut functions, PROLOG_SOURCES)?;
                Ok(functions)
            }

            #native_driver

            #(#modules)*

            #plain_rs
        };

        // Atoms: those the code names (a template's atoms are read with
        // its text).
        let mut used = std::collections::HashSet::new();
        field_idents_in(&body, &mut used);
        let atoms: Vec<&(Atom, Ident)> = self
            .atoms
            .iter()
            .filter(|(_, id)| used.contains(&id.to_string()))
            .collect();
        // A field named as its atom needs no doc (`Atoms::new` shows the
        // text of every one).
        let atom_fields = atoms.iter().map(|(a, id)| {
            if *id == a.as_str() {
                quote!(pub #id: Atom,)
            } else {
                let doc = format!(" `{}`", quote_atom(a.as_str()));
                quote!(#[doc = #doc] pub #id: Atom,)
            }
        });
        let atom_inits = atoms.iter().map(|(a, id)| {
            let lit = Literal::string(a.as_str());
            quote!(#id: Atom::intern(#lit),)
        });
        quote! {
            #[allow(unused_imports)]
            use ::sitlog_runtime::prelude::*;

            #body

            /// The atoms the program's code names, interned once.
            #[allow(dead_code, non_snake_case, clippy::all)]
            pub struct Atoms { #(#atom_fields)* }

            #[allow(clippy::all)]
            impl Atoms {
                fn new() -> Atoms {
                    Atoms { #(#atom_inits)* }
                }
            }
        }
    }

    /// DM `dm`'s module and which of the per-DM functions it has.
    fn emit_dm(&self, dm: &crate::ir::IrDm, dm_ix: usize, module: &Ident) -> DmItems {
        let none = Term::atom(none_marker());
        let dm_lit = Literal::u32_unsuffixed(dm_ix as u32);
        let mut namer = Namer::default();
        let mut vnames = Vec::new();
        let mut fns = Vec::new();
        let mut rows = Vec::new();
        let mut instantiate_arms = Vec::new();
        let mut templates = Vec::new();
        let mut select_arms = Vec::new();
        let mut run_arms = Vec::new();
        let mut native_ixs = Vec::new();
        let mut exit_arms = Vec::new();
        // A DM's situations with native code have no term code (they run
        // natively with the history kept or not); when their values do not
        // convert, the machine runs them from their templates, as the
        // interpreter does.
        let native = self.mir_types.as_ref().and_then(|t| {
            self.native_code(dm, dm_ix, &t.dms[dm_ix])
                .ok()
                .filter(|n| n.native_sits > 0)
        });
        for (i, s) in dm.situations.iter().enumerate() {
            let f = self.store.args(s.template);
            let id_text = self.store.writeq(f[1]);
            let base = match self.store.value(f[1]) {
                Value::Var(_) => "Any".to_owned(),
                _ => match self.store.functor(f[1]) {
                    Some((name, _)) => camel(name.as_str()),
                    None => format!("S{i}"),
                },
            };
            let vname = ident(&namer.fresh(base));
            vnames.push(vname.clone());
            let ix = Literal::u32_unsuffixed(i as u32);
            let kind = match s.kind {
                Kind::Final => quote!(Final),
                Kind::Recursive => quote!(Recursive),
                Kind::Perceptual => quote!(Perceptual),
            };
            // Its row of `SITUATIONS`: a situation that runs as code by its
            // compiled id (the machine asks no cheap filter of it), another
            // by its id's functor.
            // (Its DM's file is its row of the program's `DMS`: a DM is written in one file.)
            let (line, col) = line_col(&s.location);
            // Where its in_arg is written (the warning of an in_arg skipped).
            let in_arg_at = s.in_arg_location.as_deref().map(|l| {
                let (line, col) = line_col(l);
                quote!(.in_arg(#line, #col))
            });
            let row = match self.mir.plan(dm_ix as u32, i as u32) {
                Some(plan) => {
                    let name = Literal::string(plan.id.0.as_str());
                    let ar = Literal::usize_unsuffixed(plan.id.1);
                    quote!(SitRow::code(Kind::#kind, #name, #ar, #line, #col))
                }
                None => match s.id_functor {
                    Some((name, arity)) => {
                        let name = Literal::string(name.as_str());
                        let ar = Literal::usize_unsuffixed(arity);
                        quote!(SitRow::template(Kind::#kind, Some((#name, #ar)), #line, #col))
                    }
                    None => quote!(SitRow::template(Kind::#kind, None, #line, #col)),
                },
            };
            rows.push(quote!(#row #in_arg_at));

            // The instance builder, for a situation that does not run as
            // code or runs natively (the machine instantiates only those).
            let nat_sit = native
                .as_ref()
                .is_some_and(|n| n.why.get(i).is_some_and(Option::is_none));
            let planned = self.mir.plan(dm_ix as u32, i as u32).is_some() && !nat_sit;
            let fname = format_ident!("sit_{}", snake(&vname.to_string()));
            let names = [
                "head",
                "id",
                "type_term",
                "in_arg",
                "out_arg",
                "prog",
                "embedded_dm",
                "diag_mod",
                "arcs",
            ];
            let mut parts = Vec::new();
            let mut fields = Vec::new();
            for (n, &t) in names.iter().zip(f) {
                let id = format_ident!("{}", n);
                let optional = !matches!(*n, "head" | "id" | "type_term" | "arcs");
                if optional && t == none {
                    fields.push(quote!(#id: None,));
                    continue;
                }
                parts.push((id.clone(), t));
                fields.push(if optional {
                    quote!(#id: Some(#id),)
                } else {
                    quote!(#id,)
                });
            }
            let mut has_template = false;
            if planned {
                templates.push(quote!(""));
            } else if let Some(text) = self.template_text(s.template) {
                templates.push(quote!(#text));
                has_template = true;
            } else {
                // A template whose text does not read back as itself: built
                // by code.
                templates.push(quote!(""));
                let body = self.builder_body(&parts);
                let prelude = Self::prelude(&body);
                let fdoc = format!(" A fresh instance of `{id_text}` (D-7).");
                fns.push(quote! {
                    #[doc = #fdoc]
                    fn #fname(p: &super::Program, store: &mut Store) -> Instance {
                        #prelude
                        #body
                        Instance { #(#fields)* }
                    }
                });
                instantiate_arms.push(quote!(#ix => Some(#fname(p, store)),));
            }

            // The situation as code, when it can be compiled.
            if let Some(plan) = self.mir.plan(dm_ix as u32, i as u32) {
                let mut base = snake(&vname.to_string());
                // Not one of the module's own `run_*` functions (a
                // situation `exit`: the original's `robocup_2015`).
                if ["exit", "situation", "native", "typed"].contains(&base.as_str()) {
                    base.push_str("_sit");
                }
                let run_name = format_ident!("run_{}", base);
                let exit_name = format_ident!("exit_{}", base);
                let code = self.situation_code(plan, &run_name, &exit_name);
                if let Some(select) = self.select_code(plan).filter(|_| !has_template) {
                    select_arms.push(quote!(#ix => { #select }));
                }
                if nat_sit {
                    // Natively, else from the template (nothing done); the
                    // step straight to the machine (native code may have
                    // left this DM: its calls run on the native stack).
                    native_ixs.push(ix.clone());
                } else {
                    run_arms.push(quote!(#ix => #run_name(p, cx).map(Visit::Go),));
                    let rdoc = format!(" A visit of `{id_text}` as code.");
                    let run = code.run;
                    fns.push(quote!(#[doc = #rdoc] #run));
                }
                // A situation with native code has no exit arcs as code:
                // its call is pushed natively and its exit arcs matched
                // there, or the machine runs its visit from its template.
                if let Some(exit) = code.exit.filter(|_| !nat_sit) {
                    exit_arms.push(quote!(#ix => #exit_name(p, saved, final_id, cx),));
                    let edoc = format!(" The exit arcs of `{id_text}` as code.");
                    fns.push(quote!(#[doc = #edoc] #exit));
                }
            }
        }
        let count = dm.situations.len();
        let native_arm = if native_ixs.is_empty() {
            quote!()
        } else {
            quote! {
                #(#native_ixs)|* => {
                    run_native(p, cx, sit).map(|s| Visit::Stop(s.unwrap_or(Step::Template)))
                }
            }
        };
        let term_code = quote! {
            match sit {
                #(#run_arms)*
                #native_arm
                _ => Err(cx.error("the situation has no compiled code", None)),
            }
        };
        // Every situation native: the program enters its frame (no
        // `run_situation` loop, no `run_native`: native code's step goes to
        // the machine).
        let all_native = run_arms.is_empty() && native_ixs.len() == count && count > 0;
        let native_items = match native {
            Some(n) if all_native => n.items,
            Some(n) => {
                let (items, run_native) = (n.items, n.run_native);
                quote!(#items #run_native)
            }
            None => quote!(),
        };
        // An atom head is the atom, `name(A, B, ..)` its name with fresh
        // variables, both made by the program's table (`DmRow::head`);
        // another is built with fresh variables by the DM's `head`.
        let head = match self.store.value(dm.head) {
            Value::Atom(_) => Some(0),
            _ => self.fresh_head(dm.head),
        };
        let head_fn = if head.is_some() {
            quote!()
        } else {
            let body = self.builder_body(&[(format_ident!("head"), dm.head)]);
            let prelude = Self::prelude(&body);
            quote! {
                /// A fresh copy of the DM's head.
                pub fn head(p: &super::Program, store: &mut Store) -> Term {
                    #prelude #body head
                }
            }
        };
        let local_names: Vec<Ident> = (0..dm.locals.len())
            .map(|i| format_ident!("l{}", i))
            .collect();
        let mut local_stmts = Vec::new();
        let mut local_entries = Vec::new();
        for ((n, v), lname) in dm.locals.iter().zip(&local_names) {
            // Each default is copied on its own (no sharing between locals).
            let e = self.builder_expr(*v);
            let a = &self.atoms[self.atom_ix[n]].1;
            local_stmts.push(quote!(let #lname = #e;));
            local_entries.push(quote!((p.atoms.#a, #lname)));
        }
        let locals_body = quote!(#(#local_stmts)*);
        let locals_prelude = Self::prelude(&locals_body);
        // A DM without locals has none (the program's `locals` gives it
        // no entries).
        let locals_fn = if dm.locals.is_empty() {
            quote!()
        } else {
            quote! {
                /// Fresh default values of the local variables (D-5).
                pub fn locals(p: &super::Program, store: &mut Store) -> Vars {
                    #locals_prelude
                    #locals_body
                    Vars::from_entries(vec![#(#local_entries),*])
                }
            }
        };
        let head_text = self.store.writeq(dm.head);
        let mod_doc = format!(" DM `{head_text}`.");
        let count_lit = Literal::usize_unsuffixed(count);
        let builders = !instantiate_arms.is_empty();
        let run_situation = if all_native {
            quote!()
        } else {
            quote! {
                /// Runs a situation that runs as code, and the compiled
                /// situations it goes to (`Cx::run_compiled`): term code
                /// goes on by itself, native code's step goes to the machine.
                pub fn run_situation(
                    p: &super::Program,
                    sit: SitIx,
                    cx: &mut Cx<'_, '_, super::Program>,
                ) -> Result<Step, RunError> {
                    cx.run_compiled(#dm_lit, sit, |cx, sit| #term_code)
                }
            }
        };
        let exits = !exit_arms.is_empty();
        let run_exit = if exits {
            quote! {
                /// The exit arcs of a recursive situation that runs as code.
                pub fn run_exit(
                    p: &super::Program,
                    sit: SitIx,
                    saved: Term,
                    final_id: Term,
                    cx: &mut Cx<'_, '_, super::Program>,
                ) -> Result<Step, RunError> {
                    match sit {
                        #(#exit_arms)*
                        _ => Err(cx.error("the situation has no compiled code", None)),
                    }
                }
            }
        } else {
            quote!()
        };
        let selects = !select_arms.is_empty();
        let select_compiled = if selects {
            quote! {
                /// Whether a compiled situation without a template is
                /// selected by `value` (its id's constant arguments, or the
                /// whole id when it is a pattern), as its plan selects.
                pub fn select_compiled(
                    p: &super::Program,
                    sit: SitIx,
                    value: Term,
                    store: &mut Store,
                ) -> bool {
                    let a = &p.atoms;
                    match sit {
                        #(#select_arms)*
                        _ => true,
                    }
                }
            }
        } else {
            quote!()
        };
        // Its row of the program's `DMS`.
        let file = Literal::string(dm.location.rsplitn(3, ':').nth(2).unwrap_or(&dm.location));
        let dm_name = Literal::string(dm.name.as_str());
        let head_row = match head {
            Some(n) => {
                let n = Literal::usize_unsuffixed(n);
                quote!(Some(#n))
            }
            None => quote!(None),
        };
        let row = quote!(DmRow::new(#dm_name, #file, #head_row));
        let instantiate = if builders {
            quote! {
                /// A fresh instance of a situation: built by code where its
                /// template's text does not read back, else a copy of its
                /// template.
                pub fn instantiate(
                    p: &super::Program,
                    sit: SitIx,
                    store: &mut Store,
                ) -> Option<Instance> {
                    match sit {
                        #(#instantiate_arms)*
                        _ => p.instance(#dm_lit, sit, store),
                    }
                }
            }
        } else {
            quote!()
        };
        let module = quote! {
            #[doc = #mod_doc]
            // Generated code: what is unused in a DM (a variable, a
            // label, a match arm) or irrefutable is left so, once here.
            #[allow(unused, irrefutable_let_patterns, break_with_label_and_loop, clippy::all)]
            pub mod #module {
                use ::sitlog_runtime::prelude::*;
                use super::{Ctx, NatResult, Program};

                pub const SITUATIONS: [SitRow; #count_lit] = [#(#rows),*];

                #head_fn

                #locals_fn

                #select_compiled

                #run_situation
                #run_exit

                pub const TEMPLATES: [&str; #count_lit] = [#(#templates),*];

                #instantiate

                #native_items

                #(#fns)*
            }
        };
        DmItems {
            module,
            row,
            head,
            builders,
            selects,
            all_native,
            exits,
        }
    }

    /// The arity of a head `name(A, B, ..)` of distinct variables (every
    /// DM's but a test's), made by the program's `SitTable::fresh_head`.
    fn fresh_head(&self, head: Term) -> Option<usize> {
        let (_, n) = self.store.functor(head)?;
        let mut seen = std::collections::HashSet::new();
        let distinct = self
            .store
            .args(head)
            .iter()
            .all(|&a| matches!(self.store.value(a), Value::Var(v) if seen.insert(v.index())));
        (distinct && !seen.is_empty()).then_some(n)
    }
}

/// A DM's module, and which of the per-DM functions the program's
/// dispatch calls it has.
struct DmItems {
    module: TokenStream,
    /// Its row of the program's `DMS` (`DmRow::new(name, file, head)`).
    row: TokenStream,
    /// The arity of a head the program's table makes (its `DmRow::head`;
    /// `None`: the DM's `head` makes it).
    head: Option<usize>,
    /// Instance builders: its own `instantiate`.
    builders: bool,
    /// Compiled situations without a template: its own `select_compiled`
    /// (the others select on their template's id, `machine::Templates`).
    selects: bool,
    /// Every situation native: no `run_situation` or `run_native`, the
    /// program calls `nat_entry`.
    all_native: bool,
    /// Recursive situations with exit arcs as code: its own `run_exit`.
    exits: bool,
}

/// The constant `i` of `k[i]` (`k`, then `[i]`), if the group is one.
fn const_index(prev: Option<&str>, g: &proc_macro2::Group) -> Option<usize> {
    if prev != Some("k") || g.delimiter() != proc_macro2::Delimiter::Bracket {
        return None;
    }
    match g.stream().into_iter().collect::<Vec<_>>().as_slice() {
        [proc_macro2::TokenTree::Literal(l)] => l.to_string().parse().ok(),
        _ => None,
    }
}

/// The constants generated code names (`k[i]`, `p.k[i]`).
fn const_uses(ts: &TokenStream, out: &mut std::collections::BTreeSet<usize>) {
    let mut prev: Option<String> = None;
    for tt in ts.clone() {
        match tt {
            proc_macro2::TokenTree::Group(g) => {
                out.extend(const_index(prev.as_deref(), &g));
                const_uses(&g.stream(), out);
                prev = None;
            }
            proc_macro2::TokenTree::Ident(i) => prev = Some(i.to_string()),
            _ => prev = None,
        }
    }
}

/// `ts` with each constant `k[i]` it names numbered `k[map[i]]`.
fn renumber_consts(ts: TokenStream, map: &HashMap<usize, usize>) -> TokenStream {
    let mut prev: Option<String> = None;
    let mut out = Vec::new();
    for tt in ts {
        match tt {
            proc_macro2::TokenTree::Group(g) => {
                let inner = match const_index(prev.as_deref(), &g).and_then(|i| map.get(&i)) {
                    Some(&j) => {
                        let j = Literal::usize_unsuffixed(j);
                        quote!(#j)
                    }
                    None => renumber_consts(g.stream(), map),
                };
                let mut group = proc_macro2::Group::new(g.delimiter(), inner);
                group.set_span(g.span());
                out.push(proc_macro2::TokenTree::Group(group));
                prev = None;
            }
            proc_macro2::TokenTree::Ident(i) => {
                prev = Some(i.to_string());
                out.push(proc_macro2::TokenTree::Ident(i));
            }
            other => {
                prev = None;
                out.push(other);
            }
        }
    }
    out.into_iter().collect()
}

/// The line and column of a `file:line:col` location, as literals.
fn line_col(location: &str) -> (Literal, Literal) {
    let mut parts = location.rsplitn(3, ':');
    let col = parts.next().and_then(|c| c.parse().ok()).unwrap_or(0);
    let line = parts.next().and_then(|l| l.parse().ok()).unwrap_or(0);
    (Literal::u32_unsuffixed(line), Literal::u32_unsuffixed(col))
}

/// The identifiers in `ts`, as text.
/// [`idents_in`] but for a method's name (`run.empty(..)`: no atom field
/// is called).
fn field_idents_in(ts: &TokenStream, out: &mut std::collections::HashSet<String>) {
    use proc_macro2::{Delimiter, TokenTree};
    let toks: Vec<TokenTree> = ts.clone().into_iter().collect();
    for (k, tt) in toks.iter().enumerate() {
        match tt {
            TokenTree::Group(g) => field_idents_in(&g.stream(), out),
            TokenTree::Ident(i) => {
                let method = k > 0
                    && matches!(&toks[k - 1], TokenTree::Punct(p) if p.as_char() == '.')
                    && matches!(toks.get(k + 1), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis);
                if !method {
                    out.insert(i.to_string());
                }
            }
            _ => {}
        }
    }
}

pub(super) fn idents_in(ts: &TokenStream, out: &mut std::collections::HashSet<String>) {
    for tt in ts.clone() {
        match tt {
            proc_macro2::TokenTree::Group(g) => idents_in(&g.stream(), out),
            proc_macro2::TokenTree::Ident(i) => {
                out.insert(i.to_string());
            }
            _ => {}
        }
    }
}
