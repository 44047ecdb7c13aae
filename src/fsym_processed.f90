!> Processed (corrected) methods for the Wisdom-Holman splitting: a second-order kernel
!> (`WH`, `WHK-M`, `WHK-L` in kick-drift-kick form, or `T2` in drift-kick-drift form) run by
!> the one kernel on a mapped state, and a symplectic corrector of order 3, 5, 7, 11 or 17
!> (J. Wisdom, M. Holman and J. Touma, *Symplectic correctors*, Fields Inst. Commun. 10
!> (1996) 217-244; J. Wisdom, AJ 131 (2006) 2294) applied at output only.
!>
!> The corrector is a stage table too: a product of Z(a, b) = drift(a h) kick(-b h)
!> drift(-2 a h) kick(b h) drift(a h) (drifts: the model's Kepler flow, any sign; kicks: the
!> interaction), adjacent drifts merged, run by the same kernel (`fsym_kernel_run`) on a copy.
!> Its coefficients a_i = i sqrt(7/40) and b_i are those of Wisdom, Holman & Touma (1996)
!> for orders 3, 5, 7, 11 and of H. Rein, D. Tamayo and G. Brown, MNRAS 489 (2019) 4632
!> for order 17, as REBOUND 5.2.2 tabulates them. For a kick-drift-kick kernel the in-map
!> ends, and the out-map starts, with S = (half kick) o (half drift) and its inverse, the map
!> that conjugates the drift-kick-drift kernel of those papers into it.
!>
!> `init` maps the user's state (x -> S C x), `run` advances the mapped state with the
!> kernel, `output` returns the corrected state C^-1 S^-1 y of a copy: going to output never
!> changes the continuing trajectory. A checkpoint is the kernel's checkpoint of the mapped
!> state behind a short header (corrector order and h), so a restart is bitwise.
module fsym_processed
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_UNKNOWN_METHOD, &
                           FSYM_ERR_SHAPE, FSYM_ERR_BAD_STEP, FSYM_ERR_NOT_INITIALIZED, &
                           FSYM_ERR_NO_MEMORY, &
                           FSYM_ERR_CHECKPOINT, fsym_report, fsym_pass
    use fsym_scheme, only: scheme_t, OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    use fsym_paper_schemes, only: fsym_scheme_by_name
    use fsym_force, only: force_model_t
    use fsym_integrator, only: integrator_t
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout, fsym_kernel_run, &
                           fsym_kernel_invalidate, fsym_kernel_slots
    implicit none
    private

    public :: fsym_processed_lookup, fsym_corrector_table, fsym_processed_maps

    !> Orders of the correctors.
    integer, parameter, public :: FSYM_CORRECTOR_ORDERS(5) = [3, 5, 7, 11, 17]
    !> Stages of an in- or out-map (`fsym_processed_maps`): enough for every order.
    integer, parameter, public :: FSYM_MAP_MAX = 5 * 16 + 4
    !> Reals of the checkpoint header (tag, corrector order, h, steps done).
    integer, parameter :: HEAD = 4
    real(wp), parameter :: PROC_TAG = 7301996.0_wp

    ! a_i = i a_1, a_1 = sqrt(7/40) (Wisdom, Holman & Touma 1996)
    real(wp), parameter :: a1 = 0.41833001326703777398908601289259374469640768464934_wp
    real(wp), parameter :: b3(1) = [-0.024900596027799867499350357910273437184309981229127_wp]
    real(wp), parameter :: b5(2) = [-0.0083001986759332891664501193034244790614366604097090_wp, &
                                    0.041500993379666445832250596517122395307183302048545_wp]
    real(wp), parameter :: b7(3) = [0.0024926811426922105779030593952776964450539008582219_wp, &
                                    -0.018270923246702131478062356884535264841652263842597_wp, &
                                    0.053964399093127498721765893493510877532452806339655_wp]
    real(wp), parameter :: b11(5) = [ &
        0.00020361579647854651301632818774633716473696537436847_wp, &
        -0.0023487215292295354188307328851055489876255097419754_wp, &
        0.012309078592019946317544564763237909911330686448336_wp, &
        -0.038121613681288650508647613260247372125243616270670_wp, &
        0.072593394748842738674253180742744961827622366521517_wp]
    real(wp), parameter :: b17(8) = [ &
        -0.0000043347415473373580190650223498124944896789841432241_wp, &
        0.000076436355227935738363241846979413475106795392377415_wp, &
        -0.00063599983075817658983166881625078545864140848560259_wp, &
        0.0033132577069380655655490196833451994080066801611459_wp, &
        -0.012071760822342291062449751726959664253913904872527_wp, &
        0.032422198864713580293681523029577130832258806467604_wp, &
        -0.065192863576377893658290760803725762027864651086787_wp, &
        0.093056103771425958591541059067553547100903397724386_wp]

    !> A kernel with a corrector, on a mapped state it holds.
    type, public :: processed_t
        private
        type(integrator_t) :: it                 ! the kernel on the mapped state
        type(scheme_t) :: sc                     ! the kernel's table
        integer :: order = 0                     ! corrector order (0: none)
        real(wp) :: h = 0.0_wp                   ! the step (the corrector depends on it)
        integer :: d = 0, n = 0
        integer :: nin = 0, nout = 0             ! stages of the in- and out-maps
        integer, allocatable :: opi(:), opo(:)
        real(wp), allocatable :: ci(:), ui(:), co(:), uo(:)
        type(kernel_state_t) :: ksi, kso
        real(wp), allocatable :: wi(:, :, :), wo(:, :, :)
        real(wp), allocatable :: qy(:, :), vy(:, :)   ! the mapped state
        integer(ik) :: steps = 0                 ! steps taken since init
        logical :: ready = .false.
    contains
        procedure :: init => processed_init           !! set up and map the user's state
        procedure :: run => processed_run             !! advance the mapped state
        procedure :: output => processed_output       !! the corrected state (of a copy)
        procedure :: mapped => processed_mapped       !! the mapped state itself
        procedure :: evaluations => processed_evaluations
            !! force-equivalent evaluations per step (a gradient counted as one)
        procedure :: nsteps => processed_nsteps       !! steps taken since init
        procedure :: checkpoint_length => processed_checkpoint_length
            !! length of the flat checkpoint array
        procedure :: save_checkpoint => processed_save_checkpoint
            !! the mapped state and the kernel state into a flat array
        procedure :: load_checkpoint => processed_load_checkpoint
            !! resume from a flat array: bitwise as if never interrupted
    end type processed_t

contains

    !> Resolve a processed label: a kernel label of `fsym_scheme_by_name`, optionally
    !> followed by `+C<k>` (k in 3, 5, 7, 11, 17), e.g. `WH+C17`, `WHK-L+C17`, `T2+C5`.
    !> Correctors need a second-order kernel of the form kick/2 drift kick/2 or drift/2 kick
    !> drift/2. On error `stat` is non-zero and the outputs are undefined.
    subroutine fsym_processed_lookup(label, kernel, order, stat, errmsg)
        character(len=*), intent(in) :: label          !! e.g. `WHK-L+C17`
        type(scheme_t), intent(inout) :: kernel        !! the kernel's table
        integer, intent(out) :: order                  !! corrector order (0: none)
        integer, intent(out), optional :: stat         !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: p, ios, st
        character(len=256) :: msg
        order = 0
        p = index(label, '+')
        if (p == 0) then
            call fsym_scheme_by_name(label, kernel, st, msg)
            if (st /= 0) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
        else
            if (p + 2 > len_trim(label) .or. scan(label(p + 1:p + 1), 'Cc') /= 1) then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(label)//'": a corrector'// &
                                 ' is written +C<order>, e.g. WH+C17', stat, errmsg)
                return
            end if
            read (label(p + 2:len_trim(label)), *, iostat=ios) order
            if (ios /= 0 .or. .not. any(FSYM_CORRECTOR_ORDERS == order) .or. &
                verify(trim(label(p + 2:)), '0123456789') /= 0) then
                order = 0
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(label)//'": corrector '// &
                                 'orders are 3, 5, 7, 11 and 17', stat, errmsg)
                return
            end if
            call fsym_scheme_by_name(label(1:p - 1), kernel, st, msg)
            if (st /= 0) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
            if (kernel_form(kernel%op, kernel%c, kernel%u) == 0) then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(label)//'": correctors '// &
                                 'need a kernel kick/2 drift kick/2 or drift/2 kick drift/2 '// &
                                 '(WH, WHK-M, WHK-L, T2)', stat, errmsg)
                return
            end if
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_processed_lookup

    !> 1: kick/2 drift kick/2 (both kicks alike); 2: drift/2 kick drift/2; 0: neither.
    pure integer function kernel_form(op, c, u)
        integer, intent(in) :: op(:)
        real(wp), intent(in) :: c(:), u(:)
        kernel_form = 0
        if (size(op) /= 3 .or. size(c) < 3 .or. size(u) < 3) return
        if (op(1) /= OP_DRIFT .and. op(2) == OP_DRIFT .and. op(3) == op(1) .and. &
            fsym_same(c(1), 0.5_wp) .and. fsym_same(c(3), 0.5_wp) .and. &
            fsym_same(u(1), u(3))) kernel_form = 1
        if (op(1) == OP_DRIFT .and. op(3) == OP_DRIFT .and. op(2) /= OP_DRIFT .and. &
            fsym_same(c(1), 0.5_wp) .and. fsym_same(c(3), 0.5_wp)) kernel_form = 2
    end function kernel_form

    !> The in-map and the out-map of the corrector of order `order` (3, 5, 7, 11, 17) for the
    !> kernel table (op, c, u) of `fsym_processed_lookup`, as stage tables run by
    !> `fsym_kernel_run` (one step of the method's h, the model's Kepler drifts and kicks):
    !> in = C(+1) then, for a kick-drift-kick kernel, S = (half kick) o (half drift); out =
    !> S^-1 then C(-1). Arrays of FSYM_MAP_MAX entries suffice; order 0 (or a kernel not of
    !> the corrector's form): nin = nout = 0.
    subroutine fsym_processed_maps(op, c, u, order, opi, ci, ui, nin, opo, co, uo, nout)
        integer, intent(in) :: op(:)                      !! the kernel's op codes
        real(wp), intent(in) :: c(:), u(:)                !! the kernel's weights
        integer, intent(in) :: order                      !! corrector order (0: none)
        integer, intent(out) :: opi(:), opo(:)            !! op codes of the in-, out-map
        real(wp), intent(out) :: ci(:), ui(:), co(:), uo(:)   !! their weights
        integer, intent(out) :: nin, nout                 !! their stages
        integer :: form, nk
        opi = OP_DRIFT; opo = OP_DRIFT
        ci = 0.0_wp; ui = 0.0_wp; co = 0.0_wp; uo = 0.0_wp
        nin = 0; nout = 0
        form = kernel_form(op, c, u)
        if (order <= 0 .or. form == 0) return
        ! in: C(+1), then S = half kick o half drift (kick-drift-kick kernels)
        call fsym_corrector_table(order, 1.0_wp, opi, ci, nk)
        nin = nk
        ! out: S^-1, then C(-1)
        if (form == 1) then
            opi(nk + 1:nk + 2) = [OP_DRIFT, op(1)]
            ci(nk + 1:nk + 2) = [0.5_wp, 0.5_wp]
            ui(nk + 2) = u(1)
            nin = nk + 2
            opo(1:2) = [op(1), OP_DRIFT]
            co(1:2) = [-0.5_wp, -0.5_wp]
            ! the inverse half kick: the same point; a gradient weight changes sign,
            ! an extrapolation shift does not
            uo(1) = merge(u(1), -u(1), op(1) == OP_EXTRAP_KICK)
            nout = 2
        end if
        call fsym_corrector_table(order, -1.0_wp, opo(nout + 1:), co(nout + 1:), nk)
        nout = nout + nk
    end subroutine fsym_processed_maps

    !> The corrector C(inv) of order k as stages (drift weights and kick weights in units of
    !> h; adjacent drifts merged, zero drifts dropped): inv = +1 maps a state to the kernel's
    !> (drift-kick-drift) state, inv = -1 is its exact inverse. `nst` returns the number of
    !> stages; arrays of at least 5 * 8 + 1 entries suffice for every order.
    subroutine fsym_corrector_table(k, inv, op, c, nst)
        integer, intent(in) :: k                  !! order: 3, 5, 7, 11 or 17
        real(wp), intent(in) :: inv               !! +1 or -1
        integer, intent(out) :: op(:)             !! stage op codes (OP_DRIFT, OP_KICK)
        real(wp), intent(out) :: c(:)             !! stage weights
        integer, intent(out) :: nst               !! number of stages
        real(wp) :: za(16), zb(16)
        integer :: j, nz
        nst = 0
        select case (k)
        case (3)
            za(1:2) = [a1, -a1]; zb(1:2) = [-inv * b3(1), inv * b3(1)]; nz = 2
        case (5, 7, 11, 17)
            select case (k)
            case (5); call pairs(b5)
            case (7); call pairs(b7)
            case (11); call pairs(b11)
            case default; call pairs(b17)
            end select
        case default
            return
        end select
        do j = 1, nz
            call put(OP_DRIFT, za(j))
            call put(OP_KICK, -zb(j))
            call put(OP_DRIFT, -2.0_wp * za(j))
            call put(OP_KICK, zb(j))
            call put(OP_DRIFT, za(j))
        end do
        if (nst > 0) then
            if (op(nst) == OP_DRIFT .and. fsym_same(c(nst), 0.0_wp)) nst = nst - 1
        end if
    contains
        subroutine pairs(b)
            real(wp), intent(in) :: b(:)
            integer :: i, mm
            mm = size(b)
            do i = 1, mm
                za(i) = -real(mm + 1 - i, wp) * a1; zb(i) = -inv * b(i)
                za(mm + i) = real(i, wp) * a1; zb(mm + i) = inv * b(mm + 1 - i)
            end do
            nz = 2 * mm
        end subroutine pairs
        subroutine put(o, x)
            integer, intent(in) :: o
            real(wp), intent(in) :: x
            if (o == OP_DRIFT .and. nst > 0) then
                if (op(nst) == OP_DRIFT) then
                    c(nst) = c(nst) + x
                    if (fsym_same(c(nst), 0.0_wp)) nst = nst - 1
                    return
                end if
            end if
            nst = nst + 1
            op(nst) = o; c(nst) = x
        end subroutine put
    end subroutine fsym_corrector_table

    !> Set up for a processed label (see `fsym_processed_lookup`), a model, the step h and the
    !> user's state (d, n), which is mapped (copied, the arrays are not changed). The model
    !> must be the one later passed to `run` and `output`. On error nothing is usable.
    subroutine processed_init(self, label, model, q, v, h, stat, errmsg)
        class(processed_t), intent(inout) :: self        !! the processed method
        character(len=*), intent(in) :: label            !! e.g. `WHK-L+C17`
        class(force_model_t), intent(inout) :: model     !! the model (a Kepler drift)
        real(wp), intent(in), contiguous :: q(:, :)      !! positions (d, n)
        real(wp), intent(in), contiguous :: v(:, :)      !! velocities (d, n)
        real(wp), intent(in) :: h                        !! the step
        integer, intent(out), optional :: stat           !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer, parameter :: MAXC = FSYM_MAP_MAX
        integer :: st, ist
        integer(ik) :: nd
        character(len=256) :: msg
        self%ready = .false.
        if (fsym_same(h, 0.0_wp) .or. .not. abs(h) <= huge(h)) then
            call fsym_report(FSYM_ERR_BAD_STEP, 'processed: the step must be finite and '// &
                             'non-zero', stat, errmsg)
            return
        end if
        if (size(q, 1) /= size(v, 1) .or. size(q, 2) /= size(v, 2)) then
            call fsym_report(FSYM_ERR_SHAPE, 'processed: q and v differ in shape', stat, errmsg)
            return
        end if
        call fsym_processed_lookup(label, self%sc, self%order, st, msg)
        if (st /= 0) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        self%d = size(q, 1); self%n = size(q, 2); self%h = h
        call self%it%init(self%sc, model, self%d, self%n, st, msg)
        if (st /= 0) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        if (allocated(self%opi)) deallocate (self%opi, self%opo, self%ci, self%ui, self%co, &
                                             self%uo)
        allocate (self%opi(MAXC), stat=ist)
        if (ist == 0) allocate (self%opo(MAXC), stat=ist)
        if (ist == 0) allocate (self%ci(MAXC), stat=ist)
        if (ist == 0) allocate (self%ui(MAXC), stat=ist)
        if (ist == 0) allocate (self%co(MAXC), stat=ist)
        if (ist == 0) allocate (self%uo(MAXC), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'processed: no memory', stat, errmsg)
            return
        end if
        call fsym_processed_maps(self%sc%op, self%sc%c, self%sc%u, self%order, self%opi, &
                                 self%ci, self%ui, self%nin, self%opo, self%co, self%uo, self%nout)
        if (allocated(self%qy)) deallocate (self%qy, self%vy)
        allocate (self%qy(self%d, self%n), self%vy(self%d, self%n))
        if (allocated(self%wi)) deallocate (self%wi, self%wo)
        call fsym_kernel_layout(self%opi(1:max(self%nin, 1)), .false., self%d, self%n, self%ksi)
        call fsym_kernel_layout(self%opo(1:max(self%nout, 1)), .false., self%d, self%n, &
                                self%kso)
        allocate (self%wi(self%d, self%n, fsym_kernel_slots(self%ksi)), stat=ist)
        if (ist == 0) allocate (self%wo(self%d, self%n, fsym_kernel_slots(self%kso)), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'processed: no memory', stat, errmsg)
            return
        end if
        self%qy = q; self%vy = v
        if (self%nin > 0) then
            call fsym_kernel_run(self%nin, self%opi(1:self%nin), self%ci(1:self%nin), &
                                 self%ui(1:self%nin), model, self%ksi, self%qy, self%vy, &
                                 self%wi, h, 1_ik, nd, st)
            if (st /= 0) then
                call fsym_report(st, 'processed: the corrector failed on the initial state', &
                                 stat, errmsg)
                return
            end if
        end if
        self%steps = 0
        self%ready = .true.
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine processed_init

    !> Advance the mapped state by nsteps steps of h (one kernel call); stops at the first
    !> failure (the mapped state after the completed steps, `stat` and `errmsg` say why).
    subroutine processed_run(self, model, nsteps, stat, errmsg)
        class(processed_t), intent(inout) :: self        !! the processed method
        class(force_model_t), intent(inout) :: model     !! the model of `init`
        integer(ik), intent(in) :: nsteps                !! steps to take
        integer, intent(out), optional :: stat           !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: st
        character(len=256) :: msg
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'processed: not set up', stat, errmsg)
            return
        end if
        call self%it%run(model, self%qy, self%vy, self%h, nsteps, st, msg)
        if (st /= 0) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        self%steps = self%steps + nsteps
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine processed_run

    !> The corrected (output) state: the out-map applied to a copy of the mapped state. The
    !> mapped state and the kernel's cache are not touched (no allocation).
    subroutine processed_output(self, model, q, v, stat, errmsg)
        class(processed_t), intent(inout) :: self        !! the processed method
        class(force_model_t), intent(inout) :: model     !! the model of `init`
        real(wp), intent(out), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(out), contiguous :: v(:, :)     !! velocities (d, n)
        integer, intent(out), optional :: stat           !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: st
        integer(ik) :: nd
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'processed: not set up', stat, errmsg)
            return
        end if
        if (size(q, 1) /= self%d .or. size(q, 2) /= self%n .or. size(v, 1) /= self%d .or. &
            size(v, 2) /= self%n) then
            call fsym_report(FSYM_ERR_SHAPE, 'processed: output arrays of the wrong shape', &
                             stat, errmsg)
            return
        end if
        q = self%qy; v = self%vy
        if (self%nout > 0) then
            call fsym_kernel_invalidate(self%kso)
            call out_map(q, v)
            if (st /= 0) then
                call fsym_report(st, 'processed: the corrector failed at output', stat, errmsg)
                return
            end if
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    contains
        subroutine out_map(x, u)
            real(wp), intent(inout) :: x(self%d, self%n), u(self%d, self%n)
            call fsym_kernel_run(self%nout, self%opo(1:self%nout), self%co(1:self%nout), &
                                 self%uo(1:self%nout), model, self%kso, x, u, self%wo, &
                                 self%h, 1_ik, nd, st)
        end subroutine out_map
    end subroutine processed_output

    !> A copy of the mapped state (the state the kernel advances).
    subroutine processed_mapped(self, q, v)
        class(processed_t), intent(in) :: self           !! the processed method
        real(wp), intent(out) :: q(:, :), v(:, :)        !! positions, velocities (d, n)
        q = self%qy; v = self%vy
    end subroutine processed_mapped

    !> Force-equivalent evaluations per step of the kernel (a gradient counted as one).
    integer function processed_evaluations(self)
        class(processed_t), intent(in) :: self           !! the processed method
        processed_evaluations = self%sc%nforce + self%sc%ngrad
    end function processed_evaluations

    !> Steps taken since `init` (or as restored by `load_checkpoint`).
    pure integer(ik) function processed_nsteps(self)
        class(processed_t), intent(in) :: self           !! the processed method
        processed_nsteps = self%steps
    end function processed_nsteps

    !> Length of the checkpoint: a header (tag, corrector order, h, steps) and the kernel's.
    integer(ik) function processed_checkpoint_length(self)
        class(processed_t), intent(inout) :: self        !! the processed method
        processed_checkpoint_length = HEAD + self%it%checkpoint_length()
    end function processed_checkpoint_length

    !> True, with the status reported, when the method is not set up or a checkpoint of
    !> `length` reals does not fit it (the entry check of save and load).
    logical function checkpoint_refused(self, length, stat, errmsg) result(refused)
        class(processed_t), intent(inout) :: self
        integer(ik), intent(in) :: length
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        refused = .true.
        if (.not. self%ready) then
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'processed: not set up', stat, errmsg)
        else if (length /= self%checkpoint_length()) then
            call fsym_report(FSYM_ERR_SHAPE, 'processed: checkpoint of the wrong length', &
                             stat, errmsg)
        else
            refused = .false.
        end if
    end function checkpoint_refused

    !> Write the checkpoint: the header and the kernel's checkpoint of the mapped state.
    subroutine processed_save_checkpoint(self, ck, stat, errmsg)
        class(processed_t), intent(inout) :: self        !! the processed method
        real(wp), intent(out) :: ck(:)                   !! the checkpoint
        integer, intent(out), optional :: stat           !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: st
        character(len=256) :: msg
        if (checkpoint_refused(self, size(ck, kind=ik), stat, errmsg)) return
        ck(1) = PROC_TAG; ck(2) = real(self%order, wp); ck(3) = self%h
        ck(4) = real(self%steps, wp)
        call self%it%save_checkpoint(self%qy, self%vy, ck(HEAD + 1:), st, msg)
        if (st /= 0) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine processed_save_checkpoint

    !> Resume from a checkpoint of the same label, h and shape (`init` first, with any
    !> state): the mapped state and the kernel state are restored bitwise. On error nothing
    !> changes.
    subroutine processed_load_checkpoint(self, ck, stat, errmsg)
        class(processed_t), intent(inout) :: self        !! the processed method
        real(wp), intent(in) :: ck(:)                    !! the checkpoint
        integer, intent(out), optional :: stat           !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: st
        character(len=256) :: msg
        if (checkpoint_refused(self, size(ck, kind=ik), stat, errmsg)) return
        if (.not. (fsym_same(ck(1), PROC_TAG) .and. fsym_same(ck(2), real(self%order, wp)) &
                   .and. fsym_same(ck(3), self%h))) then
            call fsym_report(FSYM_ERR_CHECKPOINT, 'processed: the checkpoint is of '// &
                             'another corrector or step', stat, errmsg)
            return
        end if
        call self%it%load_checkpoint(self%qy, self%vy, ck(HEAD + 1:), st, msg)
        if (st /= 0) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        self%steps = int(ck(4), ik)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine processed_load_checkpoint

end module fsym_processed
