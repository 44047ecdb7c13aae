!> The scenes of the study of S. A. Chin, *Forward and non-forward symplectic integrators in
!> solving classical dynamics problems*, Int. J. Comput. Math. 84(6), 729-747 (2007),
!> doi:10.1080/00207160701458476, arXiv:0704.3273 (see `fsym_study`). Each scene computes
!> what one figure needs and writes `<out>/<scene>.h5` (layout in doc/h5-layout.md); the
!> `results` scene writes `<out>/results.h5`, the numbers behind doc/results.md (rendered by
!> scripts/report_results.py). Arithmetic comes from the library; this module only drives
!> it. Scenes share no module variables: the run's settings travel in a `study_t`.
module fsym_study_scenes
    use, intrinsic :: iso_fortran_env, only: output_unit
    use fsym
    use fsym_kinds, only: fsym_same
    use fsym_h5, only: h5_file_t, fsym_h5_safe_name, fsym_h5md_header, fsym_make_dir, &
                       fsym_check_writable, fsym_exit_failure
    use fsym_diagnostics, only: coefficient_tracker_t
    implicit none
    private

    public :: study_init, study_scene, study_say, study_die

    integer, parameter :: NPER = 5000          ! steps per period in the coefficient runs
    integer, parameter :: NPER_POINTS = 400    ! steps per period in the force-point scenes
    integer, parameter :: NSLAB = 1024         ! samples per slab written to HDF5
    integer, parameter :: NPERIODS = 2         ! periods shown by the coefficient scenes
    integer, parameter :: NLADDER(4) = [1000, 2000, 5000, 10000]  ! results: steps per period
    character(len=*), parameter, public :: SCENES(*) = [character(len=8) :: 'eng3f', &
        'backfr', 'back3f', 'eng4f', 'back4f', 'eng4f2', 'back4f2', 'acoef', 'eng5f', &
        'back5f', 'eng6f', 'back6f', 'scanm2', 'scangfr5', 'results']
        !! every scene, in the order `--all` runs them: the one list of scene names (the
        !! study writes it to `<out>/scenes.txt`, which the report and plot scripts read)
    character(len=*), parameter, public :: SCENE_KINDS(*) = [character(len=12) :: &
        'coefficients', 'points', 'points', 'coefficients', 'points', 'coefficients', &
        'points', 'acoef', 'coefficients', 'points', 'coefficients', 'points', 'scan', &
        'scan', 'results']
        !! the kind of each scene of SCENES (what its file holds, hence how it is drawn):
        !! coefficient curves, force points, the GFR5 backward step, a scan, the results
    character(len=*), parameter :: UNIT_SYSTEM = 'Kepler units: G M = 1, m = 1; length L '// &
        '(the orbit starts at q = (10, 0) L), time T = sqrt(L^3/(G M)); energies per unit '// &
        'mass in L^2 T-2; coefficients carry T-4 from the division by eps^4'
        !! the unit system of every file, stated in `h5md/modules/units` and `parameters`

    !> The settings of a study run, passed to every scene.
    type, public :: study_t
        character(len=:), allocatable :: outdir  !! directory of the HDF5 files
        real(wp) :: period = 0.0_wp              !! period P of the paper's orbit
        real(wp) :: q0(2) = 0.0_wp               !! start position
        real(wp) :: v0(2) = 0.0_wp               !! start velocity
        type(kepler_model_t) :: kep              !! the force model (mu = 1)
    end type study_t

    !> Summary of one coefficient run.
    type :: summary_t
        character(len=FSYM_NAME_LEN) :: name = ''
        logical :: forward = .false.
        integer :: nforce = 0, ngrad = 0
        real(wp) :: emax = 0.0_wp     ! max |energy coefficient| over the first period
        real(wp) :: pend = 0.0_wp     ! precession coefficient at t = P
        real(wp) :: eend = 0.0_wp     ! energy coefficient at t = P
        real(wp) :: eend2 = 0.0_wp    ! energy coefficient at t = 2P (runs of 2 periods)
        real(wp) :: pend2 = 0.0_wp    ! precession coefficient at t = 2P
    end type summary_t

contains

    !> Settings for a run writing into `out` (created with its parents when missing, by
    !> `mkdir(2)`, no shell).
    subroutine study_init(cx, out)
        type(study_t), intent(out) :: cx         !! the settings
        character(len=*), intent(in) :: out      !! directory for the HDF5 files
        integer :: st
        character(len=256) :: msg
        cx%outdir = trim(out)
        call kepler_paper_orbit(cx%q0, cx%v0, cx%period)
        call fsym_make_dir(cx%outdir)
        call fsym_check_writable(cx%outdir//'/results.h5', st, msg)
        if (st /= 0) call study_die('cannot write into the output directory '//cx%outdir)
        call write_scene_list(cx%outdir//'/scenes.txt')
    end subroutine study_init

    !> `<out>/scenes.txt`: every scene and its kind, one `name kind` line each, in the order
    !> `--all` runs them (scripts/plot_figures.py and scripts/report_results.py take the
    !> scene names from it, so SCENES is their one source).
    subroutine write_scene_list(path)
        character(len=*), intent(in) :: path     !! the file (replaced)
        integer :: u, ios, ios_close, k
        if (size(SCENE_KINDS) /= size(SCENES)) call study_die('SCENE_KINDS does not match SCENES')
        open (newunit=u, file=path, status='replace', action='write', iostat=ios)
        if (ios /= 0) call study_die('cannot write '//path)
        do k = 1, size(SCENES)
            if (ios == 0) write (u, '(a,1x,a)', iostat=ios) trim(SCENES(k)), &
                trim(SCENE_KINDS(k))
        end do
        close (u, iostat=ios_close)
        if (ios /= 0 .or. ios_close /= 0) call study_die('cannot write '//path)
    end subroutine write_scene_list

    !> Run one scene by name.
    subroutine study_scene(cx, name)
        type(study_t), intent(inout) :: cx       !! the settings
        character(len=*), intent(in) :: name     !! scene name (one of SCENES)
        call study_say('scene '//trim(name))
        select case (trim(name))
        case ('eng3f'); call scene_coefficients(cx, 'eng3f', [character(len=16) :: 'FR', 'A', &
                                                 'A''', 'RKN'])
        case ('eng4f'); call scene_coefficients(cx, 'eng4f', [character(len=16) :: 'M1', &
                                                 'M1(-0.2)', 'M1(-0.1)', 'M1(-1/24)', 'C'])
        case ('eng4f2'); call scene_coefficients(cx, 'eng4f2', [character(len=16) :: &
                                                  'M2(-0.1)', 'M2(-0.5)', 'M2(-1)', 'M2(-2)', 'C'])
        case ('eng5f'); call scene_coefficients(cx, 'eng5f', [character(len=16) :: &
                                                 'GFR5(0.3)', 'GFR5(0.5)', 'GFR5(1)', 'A5', 'C'])
        case ('eng6f'); call scene_coefficients(cx, 'eng6f', [character(len=16) :: 'BM', 'A6', &
                                                 'A6''', 'C'])
        case ('backfr'); call scene_points(cx, 'backfr', [character(len=16) :: 'FR'], .true.)
        case ('back3f'); call scene_points(cx, 'back3f', [character(len=16) :: 'FR', 'A', &
                                           'RKN'], .false.)
        case ('back4f'); call scene_points(cx, 'back4f', [character(len=16) :: 'M1', &
                                           'M1(-1/24)', 'C'], .false.)
        case ('back4f2'); call scene_points(cx, 'back4f2', [character(len=16) :: 'M2(-0.1)', &
                                            'M2(-0.5)', 'C'], .false.)
        case ('back5f'); call scene_points(cx, 'back5f', [character(len=16) :: 'GFR5(0.3)', &
                                           'GFR5(1)', 'A5'], .false.)
        case ('back6f'); call scene_points(cx, 'back6f', [character(len=16) :: 'BM', 'A6'], &
                                           .false.)
        case ('acoef'); call scene_acoef(cx)
        case ('scanm2'); call scene_scan_m2(cx)
        case ('scangfr5'); call scene_scan_gfr5(cx)
        case ('results'); call scene_results(cx)
        case default; call study_die('unknown scene '//trim(name))
        end select
    end subroutine study_scene

    !> A progress line on standard output.
    subroutine study_say(text)
        character(len=*), intent(in) :: text  !! the line
        write (output_unit, '(a)') '[fsym-study] '//text
        flush (output_unit)
    end subroutine study_say

    !> Stop the program with a message (programs only; the library never stops).
    subroutine study_die(text)
        character(len=*), intent(in) :: text  !! the message
        call fsym_exit_failure('fsym-study', text)    ! flushed, exit 1, no crash at exit
    end subroutine study_die

    !> Stop with the message when a status is non-zero.
    subroutine need(stat, text)
        integer, intent(in) :: stat
        character(len=*), intent(in) :: text
        if (stat /= 0) call study_die(trim(text))
    end subroutine need

    ! ---------------------------------------------------------------- steppers

    !> A compensated stepper for a label (any `fsym_scheme_by_name` label or RKN) at t0.
    subroutine new_stepper(cx, label, s, t0)
        type(study_t), intent(inout) :: cx
        character(len=*), intent(in) :: label
        class(stepper_t), allocatable, intent(inout) :: s
        real(wp), intent(in) :: t0
        integer :: st
        character(len=256) :: msg
        call fsym_new_stepper(trim(label), cx%kep, 2, 1, s, st, msg, compensated=.true., t0=t0)
        call need(st, msg)
    end subroutine new_stepper

    !> A compensated stepper for a scheme built from parameters (scans).
    subroutine stepper_of(cx, sch, s)
        type(study_t), intent(inout) :: cx
        type(scheme_t), intent(in) :: sch
        class(stepper_t), allocatable, intent(inout) :: s
        type(integrator_t) :: it
        integer :: st
        character(len=256) :: msg
        call it%init(sch, cx%kep, 2, 1, st, msg, compensated=.true.)
        call need(st, msg)
        if (allocated(s)) deallocate (s)
        allocate (s, source=it)
    end subroutine stepper_of

    !> The run's parameters under `parameters/<safe name>`: label, counts, flags, eps and
    !> the coefficient table of a splitting method.
    subroutine method_attrs(f, g, s, eps)
        type(h5_file_t), intent(inout) :: f
        character(len=*), intent(in) :: g
        class(stepper_t), intent(in) :: s
        real(wp), intent(in) :: eps
        type(scheme_t) :: sch
        call f%set_attr(g, 'method', trim(s%name()))
        call f%set_attr(g, 'forward', merge(1, 0, s%is_forward()))
        call f%set_attr(g, 'symplectic', merge(1, 0, s%is_symplectic()))
        call f%set_attr(g, 'splitting', merge(1, 0, s%is_splitting()))
        call f%set_attr(g, 'forces_per_step', s%forces_per_step())
        call f%set_attr(g, 'gradients_per_step', s%gradients_per_step())
        call f%set_attr(g, 'force_evaluations', int(s%force_evaluations()))
        call f%set_attr(g, 'gradient_evaluations', int(s%gradient_evaluations()))
        call f%set_attr(g, 'eps', eps)
        call f%set_attr(g, 'compensated_summation', 1)
        select type (s)
        type is (integrator_t)
            sch = s%scheme()
            call f%set_attr(g, 'op', sch%op)
            call f%set_attr(g, 'c', sch%c)
            call f%set_attr(g, 'u', sch%u)
            call f%set_attr(g, 'op_codes', 'OP_DRIFT=1 OP_KICK=2 OP_GRAD_KICK=3 '// &
                            'OP_EXTRAP_KICK=4')
        end select
    end subroutine method_attrs

    !> H5MD metadata (h5md group, units module) and the file's `parameters` group.
    subroutine file_header(cx, f, scene, eps)
        type(study_t), intent(inout) :: cx
        type(h5_file_t), intent(inout) :: f
        character(len=*), intent(in) :: scene
        real(wp), intent(in) :: eps
        call fsym_h5md_header(f, 'fsym-study', FSYM_VERSION, UNIT_SYSTEM)
        call f%set_attr('parameters', 'scene', scene)
        call f%set_attr('parameters', 'eps', eps)
        call f%set_attr('parameters', 'period', cx%period)
        call f%set_attr('parameters', 'mu', cx%kep%mu)
        call f%set_attr('parameters', 'q0', cx%q0)
        call f%set_attr('parameters', 'v0', cx%v0)
    end subroutine file_header

    !> H5MD box of a particle group (open 2D space) and its `label`.
    subroutine particle_group(f, g, label)
        type(h5_file_t), intent(inout) :: f
        character(len=*), intent(in) :: g, label
        call f%set_attr(g, 'label', trim(label))
        call f%set_attr(g//'/box', 'dimension', 2)
        call f%set_attr(g//'/box', 'boundary', [character(len=4) :: 'none', 'none'])
    end subroutine particle_group

    !> The `unit` attribute of a dataset.
    subroutine unit(f, path, u)
        type(h5_file_t), intent(inout) :: f
        character(len=*), intent(in) :: path, u
        call f%set_attr(path, 'unit', u)
    end subroutine unit

    ! ---------------------------------------------------------------- coefficient runs

    !> Integrate `nsteps` steps of eps = P/nper from the paper's start state; return the
    !> summary. With `f`, also write every step's state and coefficients in slabs; with
    !> `curve`, return the energy (row 1) and precession (row 2) coefficients after each of
    !> the first size(curve, 2) steps.
    subroutine coefficient_run(cx, s, nper, nsteps, res, f, curve)
        type(study_t), intent(inout) :: cx
        class(stepper_t), intent(inout) :: s
        integer, intent(in) :: nper, nsteps
        type(summary_t), intent(out) :: res
        type(h5_file_t), intent(inout), optional :: f
        real(wp), intent(out), optional :: curve(:, :)
        type(coefficient_tracker_t) :: tr
        real(wp) :: q(2, 1), v(2, 1), eps
        real(wp) :: bt(NSLAB), bq(2, 1, NSLAB), bv(2, 1, NSLAB), be(NSLAB), bp(NSLAB)
        integer(ik) :: bs(NSLAB)
        integer :: j, nb, st
        character(len=256) :: msg
        character(len=:), allocatable :: pg, og
        eps = cx%period / nper
        q(:, 1) = cx%q0; v(:, 1) = cx%v0
        call tr%init(cx%q0, cx%v0, eps)
        res%name = s%name()
        nb = 0
        if (present(f)) then
            pg = 'particles/'//fsym_h5_safe_name(res%name)
            og = 'observables/'//fsym_h5_safe_name(res%name)
            call sample(0)
        end if
        do j = 1, nsteps
            call s%step(cx%kep, q, v, eps, st, msg)
            call need(st, trim(res%name)//': '//msg)
            call tr%update(q(:, 1), v(:, 1))
            if (present(curve)) then
                if (j <= size(curve, 2)) curve(:, j) = [tr%energy, tr%precession]
            end if
            if (j == nper) then
                res%emax = tr%energy_max
                res%pend = tr%precession
                res%eend = tr%energy
            end if
            if (j == 2 * nper) then
                res%eend2 = tr%energy
                res%pend2 = tr%precession
            end if
            if (present(f)) call sample(j)
        end do
        if (present(f)) then
            call flush_slab()
            call particle_group(f, pg, res%name)
            call f%set_attr(og, 'label', trim(res%name))
            call unit(f, pg//'/position/time', 'T'); call unit(f, pg//'/position/value', 'L')
            call unit(f, pg//'/velocity/time', 'T')
            call unit(f, pg//'/velocity/value', 'L T-1')
            call unit(f, og//'/energy_coefficient/time', 'T')
            call unit(f, og//'/energy_coefficient/value', 'T-4')
            call unit(f, og//'/precession_coefficient/time', 'T')
            call unit(f, og//'/precession_coefficient/value', 'rad T-4')
            call method_attrs(f, 'parameters/'//fsym_h5_safe_name(res%name), s, eps)
        end if
        res%forward = s%is_forward()
        res%nforce = s%forces_per_step()
        res%ngrad = s%gradients_per_step()
    contains
        subroutine sample(j)
            integer, intent(in) :: j
            nb = nb + 1
            bs(nb) = j
            bt(nb) = j * eps
            bq(:, :, nb) = q
            bv(:, :, nb) = v
            be(nb) = tr%energy
            bp(nb) = tr%precession
            if (nb == NSLAB) call flush_slab()
        end subroutine sample
        subroutine flush_slab()
            if (nb == 0) return
            call f%append(pg//'/position/step', bs(1:nb))
            call f%append(pg//'/position/time', bt(1:nb))
            call f%append(pg//'/position/value', bq(:, :, 1:nb))
            call f%append(pg//'/velocity/step', bs(1:nb))
            call f%append(pg//'/velocity/time', bt(1:nb))
            call f%append(pg//'/velocity/value', bv(:, :, 1:nb))
            call f%append(og//'/energy_coefficient/step', bs(1:nb))
            call f%append(og//'/energy_coefficient/time', bt(1:nb))
            call f%append(og//'/energy_coefficient/value', be(1:nb))
            call f%append(og//'/precession_coefficient/step', bs(1:nb))
            call f%append(og//'/precession_coefficient/time', bt(1:nb))
            call f%append(og//'/precession_coefficient/value', bp(1:nb))
            nb = 0
        end subroutine flush_slab
    end subroutine coefficient_run

    !> Coefficient scene: each method over NPERIODS periods at eps = P/NPER.
    subroutine scene_coefficients(cx, scene, labels)
        type(study_t), intent(inout) :: cx
        character(len=*), intent(in) :: scene
        character(len=*), intent(in) :: labels(:)
        type(h5_file_t) :: f
        class(stepper_t), allocatable :: s
        type(summary_t) :: res
        character(len=160) :: line
        integer :: m, st
        character(len=256) :: msg
        call f%create(cx%outdir//'/'//scene//'.h5')
        call file_header(cx, f, scene, cx%period / NPER)
        call f%set_attr('parameters', 'methods', labels)
        do m = 1, size(labels)
            call new_stepper(cx, labels(m), s, 0.0_wp)
            call coefficient_run(cx, s, NPER, NPERIODS * NPER, res, f)
            write (line, '(2x,a12,a,es14.6,a,es14.6)') trim(labels(m)), &
                ' max|E coeff| (1 period)', res%emax, '   precession coeff at P', res%pend
            call study_say(trim(line))
        end do
        call f%close(st, msg); call need(st, msg)
        call study_say('  wrote '//cx%outdir//'/'//scene//'.h5')
    end subroutine scene_coefficients

    ! ---------------------------------------------------------------- force points

    !> Force-point scene: each method steps twice at eps = P/400 from the exact state two
    !> steps before the pericentre; force-evaluation points, step-end positions and (for FR
    !> with `substeps`) the positions after each T2 substep; plus the exact orbit nearby.
    subroutine scene_points(cx, scene, labels, substeps)
        type(study_t), intent(inout) :: cx
        character(len=*), intent(in) :: scene
        character(len=*), intent(in) :: labels(:)
        logical, intent(in) :: substeps
        integer, parameter :: NSTEP = 2, NEXACT = 401
        type(h5_file_t) :: f
        class(stepper_t), allocatable :: s
        type(trace_recorder_t) :: tr
        real(wp) :: eps, t0, q(2, 1), v(2, 1), qs(2, 1, NSTEP + 1), ts(NSTEP + 1)
        real(wp) :: qe(2, 1, NEXACT), te(NEXACT)
        integer(ik) :: steps(NSTEP + 1)
        integer :: m, j, st
        character(len=256) :: msg
        character(len=:), allocatable :: g, safe
        character(len=160) :: line
        eps = cx%period / NPER_POINTS
        t0 = 0.5_wp * cx%period - NSTEP * eps
        call f%create(cx%outdir//'/'//scene//'.h5')
        call file_header(cx, f, scene, eps)
        call f%set_attr('parameters', 'methods', labels)
        call f%set_attr('parameters', 't_start', t0)
        ! the exact orbit from 3 steps before to 3 steps after the pericentre
        do j = 1, NEXACT
            te(j) = 0.5_wp * cx%period + 3.0_wp * eps * (2.0_wp * (j - 1) / (NEXACT - 1) - 1.0_wp)
            call kepler_exact(cx%q0, cx%v0, te(j), qe(:, 1, j), v(:, 1), st)
            call need(st, 'kepler_exact failed')
        end do
        call f%write('exact/position/time', te)
        call f%write('exact/position/value', qe)
        call unit(f, 'exact/position/time', 'T'); call unit(f, 'exact/position/value', 'L')
        call tr%init(2, 1, 256, st, msg); call need(st, msg)
        do m = 1, size(labels)
            call kepler_exact(cx%q0, cx%v0, t0, q(:, 1), v(:, 1), st)
            call need(st, 'kepler_exact failed')
            call new_stepper(cx, labels(m), s, t0)
            call tr%clear()
            qs(:, :, 1) = q; ts(1) = t0; steps(1) = 0
            do j = 1, NSTEP
                call s%step(cx%kep, q, v, eps, st, msg, recorder=tr)
                call need(st, msg)
                qs(:, :, j + 1) = q; ts(j + 1) = t0 + j * eps; steps(j + 1) = j
            end do
            safe = fsym_h5_safe_name(s%name())
            g = 'particles/'//safe
            call f%write(g//'/position/step', steps)
            call f%write(g//'/position/time', ts)
            call f%write(g//'/position/value', qs)
            call unit(f, g//'/position/time', 'T'); call unit(f, g//'/position/value', 'L')
            call particle_group(f, g, s%name())
            call method_attrs(f, 'parameters/'//safe, s, eps)
            g = 'force_evaluations/'//safe
            call f%write(g//'/step', tr%step(1:tr%count))
            call f%write(g//'/stage', tr%stage(1:tr%count))
            call f%write(g//'/kind', tr%kind(1:tr%count))
            call f%write(g//'/position', tr%q(:, :, 1:tr%count))
            call unit(f, g//'/position', 'L')
            call f%set_attr(g, 'label', trim(s%name()))
            call f%set_attr(g, 'kind_codes', 'EVAL_FORCE=1 EVAL_GRADIENT=2 '// &
                            'EVAL_EXTRAPOLATED=3')
            call f%set_attr(g, 'dropped', int(tr%dropped))
            write (line, '(2x,a12,i4,a)') trim(labels(m)), tr%count, ' force points recorded'
            call study_say(trim(line))
            if (substeps .and. trim(labels(m)) == 'FR') call fr_substeps(cx, f, t0, eps, NSTEP)
        end do
        call f%close(st, msg); call need(st, msg)
        call study_say('  wrote '//cx%outdir//'/'//scene//'.h5')
    end subroutine scene_points

    !> FR as three T2 substeps of a1 eps, a0 eps, a1 eps: the positions after each substep
    !> (points 1, 1a, 1b, 2, 2a, 2b, 3 of the paper's figure).
    subroutine fr_substeps(cx, f, t0, eps, nstep)
        type(study_t), intent(inout) :: cx
        type(h5_file_t), intent(inout) :: f
        real(wp), intent(in) :: t0, eps
        integer, intent(in) :: nstep
        class(stepper_t), allocatable :: s
        real(wp) :: a(3), a0, a1, a2, q(2, 1), v(2, 1), qs(2, 1, 3 * nstep + 1)
        integer :: j, i, st
        character(len=256) :: msg
        call fsym_gfr5_coefficients(0.0_wp, a0, a1, a2, st, msg); call need(st, msg)
        a = [a1, a0, a1]
        call kepler_exact(cx%q0, cx%v0, t0, q(:, 1), v(:, 1), st)
        call need(st, 'kepler_exact failed')
        call new_stepper(cx, 'T2', s, t0)
        qs(:, :, 1) = q
        do j = 1, nstep
            do i = 1, 3
                call s%step(cx%kep, q, v, a(i) * eps, st, msg); call need(st, msg)
                qs(:, :, 3 * (j - 1) + i + 1) = q
            end do
        end do
        call f%write('substeps/FR/position/value', qs)
        call unit(f, 'substeps/FR/position/value', 'L')
        call f%set_attr('substeps/FR', 'fractions', a)
    end subroutine fr_substeps

    ! ---------------------------------------------------------------- GFR5 coefficients

    subroutine scene_acoef(cx)
        type(study_t), intent(inout) :: cx
        integer, parameter :: NA = 201
        type(h5_file_t) :: f
        real(wp) :: al(NA), c(3, NA)
        integer :: j, st
        character(len=256) :: msg
        call f%create(cx%outdir//'/acoef.h5')
        do j = 1, NA
            al(j) = 2.0_wp * (j - 1) / (NA - 1)
            call fsym_gfr5_coefficients(al(j), c(1, j), c(2, j), c(3, j), st, msg)
            call need(st, msg)
        end do
        call file_header(cx, f, 'acoef', 0.0_wp)
        call f%write('gfr5/alpha', al)
        call f%write('gfr5/a0', c(1, :))
        call f%write('gfr5/a1', c(2, :))
        call f%write('gfr5/a2', c(3, :))
        j = minloc(abs(c(1, :)), 1)
        call f%set_attr('gfr5', 'alpha_least_negative_a0', al(j))
        call f%close(st, msg); call need(st, msg)
        call study_say('  a0 least negative at alpha = '//num(al(j)))
        call study_say('  wrote '//cx%outdir//'/acoef.h5')
    end subroutine scene_acoef

    ! ---------------------------------------------------------------- scans

    !> Summary of M2(t1) at eps = P/NPER over one period.
    subroutine m2_at(cx, t1, res)
        type(study_t), intent(inout) :: cx
        real(wp), intent(in) :: t1
        type(summary_t), intent(out) :: res
        type(scheme_t) :: sch
        class(stepper_t), allocatable :: s
        integer :: st
        character(len=256) :: msg
        call fsym_scheme_m2(t1, sch, st, msg); call need(st, msg)
        call stepper_of(cx, sch, s)
        call coefficient_run(cx, s, NPER, NPER, res)
    end subroutine m2_at

    !> The M2 scan over t1 and the bisected zero of the precession at t = P.
    subroutine m2_scan(cx, t1, e, p, t1zero, found)
        type(study_t), intent(inout) :: cx
        real(wp), allocatable, intent(out) :: t1(:), e(:), p(:)
        real(wp), intent(out) :: t1zero
        logical, intent(out) :: found
        type(summary_t) :: r
        real(wp) :: lo, hi, plo, mid
        integer :: j, it
        t1 = [(-2.5_wp + 0.1_wp * (j - 1), j=1, 25)]
        allocate (e(size(t1)), p(size(t1)))
        do j = 1, size(t1)
            call m2_at(cx, t1(j), r)
            e(j) = r%emax; p(j) = r%pend
        end do
        found = .false.; t1zero = 0.0_wp
        do j = 1, size(t1) - 1
            if (.not. fsym_same(sign(1.0_wp, p(j)), sign(1.0_wp, p(j + 1)))) then
                lo = t1(j); hi = t1(j + 1); plo = p(j)
                do it = 1, 60
                    mid = 0.5_wp * (lo + hi)
                    call m2_at(cx, mid, r)
                    if (fsym_same(sign(1.0_wp, r%pend), sign(1.0_wp, plo))) then
                        lo = mid; plo = r%pend
                    else
                        hi = mid
                    end if
                    if (hi - lo < 1.0e-9_wp) exit
                end do
                t1zero = 0.5_wp * (lo + hi); found = .true.
                exit
            end if
        end do
    end subroutine m2_scan

    subroutine scene_scan_m2(cx)
        type(study_t), intent(inout) :: cx
        type(h5_file_t) :: f
        real(wp), allocatable :: t1(:), e(:), p(:)
        real(wp) :: t1zero
        logical :: found
        integer :: st
        character(len=256) :: msg
        call f%create(cx%outdir//'/scanm2.h5')
        call m2_scan(cx, t1, e, p, t1zero, found)
        call file_header(cx, f, 'scanm2', cx%period / NPER)
        call f%write('scan/t1', t1)
        call f%write('scan/energy_max', e)
        call f%write('scan/precession_at_P', p)
        call unit(f, 'scan/energy_max', 'T-4'); call unit(f, 'scan/precession_at_P', 'rad T-4')
        call f%set_attr('scan', 'zero_found', merge(1, 0, found))
        call f%set_attr('scan', 't1_zero', t1zero)
        call f%close(st, msg); call need(st, msg)
        if (found) then
            call study_say('  precession at t = P crosses zero at t1 = '//num(t1zero))
        else
            call study_say('  precession at t = P does not cross zero on the grid')
        end if
        call study_say('  wrote '//cx%outdir//'/scanm2.h5')
    end subroutine scene_scan_m2

    !> The GFR5 scan over alpha: max |energy coefficient| and precession at P.
    subroutine gfr5_scan(cx, al, e, p)
        type(study_t), intent(inout) :: cx
        real(wp), allocatable, intent(out) :: al(:), e(:), p(:)
        type(scheme_t) :: sch
        class(stepper_t), allocatable :: s
        type(summary_t) :: r
        integer :: j, st
        character(len=256) :: msg
        al = [(0.025_wp * j, j=0, 80)]
        allocate (e(size(al)), p(size(al)))
        do j = 1, size(al)
            call fsym_scheme_gfr5(al(j), sch, st, msg); call need(st, msg)
            call stepper_of(cx, sch, s)
            call coefficient_run(cx, s, NPER, NPER, r)
            e(j) = r%emax; p(j) = r%pend
        end do
    end subroutine gfr5_scan

    subroutine scene_scan_gfr5(cx)
        type(study_t), intent(inout) :: cx
        type(h5_file_t) :: f
        real(wp), allocatable :: al(:), e(:), p(:)
        integer :: st
        character(len=256) :: msg
        call f%create(cx%outdir//'/scangfr5.h5')
        call gfr5_scan(cx, al, e, p)
        call file_header(cx, f, 'scangfr5', cx%period / NPER)
        call f%write('scan/alpha', al)
        call f%write('scan/energy_max', e)
        call f%write('scan/precession_at_P', p)
        call unit(f, 'scan/energy_max', 'T-4'); call unit(f, 'scan/precession_at_P', 'rad T-4')
        call f%set_attr('scan', 'alpha_least_energy', al(minloc(e, 1)))
        call f%set_attr('scan', 'alpha_least_precession', al(minloc(abs(p), 1)))
        call f%close(st, msg); call need(st, msg)
        call study_say('  least energy error at alpha = '//num(al(minloc(e, 1)))// &
                       ', least |precession| at alpha = '//num(al(minloc(abs(p), 1))))
        call study_say('  wrote '//cx%outdir//'/scangfr5.h5')
    end subroutine scene_scan_gfr5

    ! ---------------------------------------------------------------- results

    !> A number with 7 significant digits.
    pure function num(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(es14.6)') x
        s = trim(adjustl(buf))
    end function num

    !> The numbers behind doc/results.md: every catalogue method and A7, A8, A7', A8',
    !> GFR5(0) and M2(t1*) (t1* the zero of M2's precession at t = P), each over two periods
    !> at eps = P/1000, P/2000, P/5000, P/10000: max |energy coefficient| over the first
    !> period, energy and precession coefficients at t = P and t = 2P, the evaluation counts
    !> of each run, and the coefficient curves over the first period at eps = P/NPER. The
    !> method attributes (eps, counts) are those of the eps = P/NPER run, the file's eps.
    subroutine scene_results(cx)
        type(study_t), intent(inout) :: cx
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        character(len=FSYM_NAME_LEN) :: label
        real(wp), allocatable :: t1(:), em(:), pm(:)
        real(wp) :: t1zero
        real(wp) :: d(size(NLADDER), 5), nfe(size(NLADDER))
        real(wp) :: nge(size(NLADDER))
        real(wp), allocatable :: curve(:, :)     ! on the heap: 2 x NPER values
        logical :: found
        type(h5_file_t) :: f
        type(summary_t) :: r
        class(stepper_t), allocatable :: s
        type(scheme_t) :: sch
        integer :: m, k, st
        character(len=256) :: msg
        character(len=:), allocatable :: g
        allocate (curve(2, NPER))
        call f%create(cx%outdir//'/results.h5')
        call file_header(cx, f, 'results', cx%period / NPER)
        call m2_scan(cx, t1, em, pm, t1zero, found)
        if (.not. found) call study_die('results: no zero of the M2 precession on the grid')
        names = [fsym_method_names(), [character(len=FSYM_NAME_LEN) :: 'A7', 'A8', 'A7''', &
                 'A8''', 'GFR5(0)', 'M2(t1*)']]
        call f%set_attr('parameters', 'methods', names)
        call f%set_attr('parameters', 'steps_per_period', NLADDER)
        call f%set_attr('parameters', 'm2_t1_zero', t1zero)
        do m = 1, size(names)
            label = names(m)
            do k = 1, size(NLADDER)
                if (trim(label) == 'M2(t1*)') then
                    call fsym_scheme_m2(t1zero, sch, st, msg); call need(st, msg)
                    call stepper_of(cx, sch, s)
                else if (trim(label) == 'GFR5(0)') then
                    call fsym_scheme_gfr5(0.0_wp, sch, st, msg); call need(st, msg)
                    call stepper_of(cx, sch, s)
                else
                    call new_stepper(cx, label, s, 0.0_wp)
                end if
                g = 'summary/'//fsym_h5_safe_name(label)
                if (NLADDER(k) == NPER) then
                    call coefficient_run(cx, s, NLADDER(k), 2 * NLADDER(k), r, curve=curve)
                    call method_attrs(f, g, s, cx%period / NPER)
                else
                    call coefficient_run(cx, s, NLADDER(k), 2 * NLADDER(k), r)
                end if
                d(k, :) = [r%emax, r%eend, r%pend, r%eend2, r%pend2]
                nfe(k) = real(s%force_evaluations(), wp)
                nge(k) = real(s%gradient_evaluations(), wp)
            end do
            call f%write(g//'/steps_per_period', real(NLADDER, wp))
            call f%write(g//'/energy_max', d(:, 1))
            call f%write(g//'/energy_at_P', d(:, 2))
            call f%write(g//'/precession_at_P', d(:, 3))
            call f%write(g//'/energy_at_2P', d(:, 4))
            call f%write(g//'/precession_at_2P', d(:, 5))
            call f%write(g//'/force_evaluations', nfe)
            call f%write(g//'/gradient_evaluations', nge)
            call f%write(g//'/energy_curve', curve(1, :))
            call f%write(g//'/precession_curve', curve(2, :))
            call unit(f, g//'/energy_curve', 'T-4')
            call unit(f, g//'/precession_curve', 'rad T-4')
            call f%set_attr(g//'/energy_curve', 'eps', cx%period / NPER)
            call f%set_attr(g//'/precession_curve', 'eps', cx%period / NPER)
            call unit(f, g//'/energy_max', 'T-4'); call unit(f, g//'/energy_at_P', 'T-4')
            call unit(f, g//'/energy_at_2P', 'T-4')
            call unit(f, g//'/precession_at_P', 'rad T-4')
            call unit(f, g//'/precession_at_2P', 'rad T-4')
            call f%set_attr(g, 'label', trim(label))
        end do
        call f%close(st, msg); call need(st, msg)
        call study_say('  '//fsym_int_text(size(names))//' methods, M2 precession zero at t1 = '// &
                       num(t1zero))
        call study_say('  wrote '//cx%outdir//'/results.h5')
    end subroutine scene_results

end module fsym_study_scenes
