!> Splitting schemes as data: the table type `scheme_t` (an operation code per stage and its
!> coefficients) with the metadata that follow from the table (order, forward, symplectic,
!> symmetric, first-same-as-last, evaluations per step), the constructor from the user's own
!> arrays that checks consistency, and the type-bound helpers. The paper's methods and the
!> label parser are in `fsym_paper_schemes`.
!>
!> A step of size h runs the stages in order on (q, v):
!>
!> * `OP_DRIFT`        q <- q + c h v
!> * `OP_KICK`         v <- v + c h a(q)
!> * `OP_GRAD_KICK`    v <- v + c h a(q) + u h^3 g(q)   (g: the gradient term, grad |a|^2)
!> * `OP_EXTRAP_KICK`  v <- v + c h a(q + u h^2 a(q))   (the gradient term by extrapolation)
!>
!> The tables know nothing of Hamiltonians: they can drive any pair of flows e^{hT}, e^{hV}.
!> The stage semantics are those of S. A. Chin, *Forward and non-forward symplectic
!> integrators in solving classical dynamics problems*, Int. J. Comput. Math. 84(6), 729-747
!> (2007), doi:10.1080/00207160701458476, arXiv:0704.3273: the gradient kick is the classical
!> form of the double commutator [V,[T,V]] (S. A. Chin, Phys. Lett. A 226(6), 344-348 (1997),
!> doi:10.1016/S0375-9601(97)00003-0), and the extrapolated kick replaces it to O(h^5) as in
!> the paper's A'.
!> Every array is allocated with `stat=`: a table too large for memory is reported as
!> `FSYM_ERR_NO_MEMORY`, never as an abort. Character results have lengths fixed by
!> specification expressions (no hidden static buffer), so the module is thread-safe.
module fsym_scheme
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_INCONSISTENT_SCHEME, &
                           FSYM_ERR_NO_MEMORY, fsym_report
    use fsym_force, only: force_model_t
    use fsym_kernel, only: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK, kernel_state_t, &
                           fsym_kernel_layout, fsym_kernel_slots, fsym_kernel_run, &
                           fsym_kernel_counts
    implicit none
    private

    ! the op codes are the kernel's (it alone knows what they do); re-exported here
    public :: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK

    !> A model of zero forces with a gradient term, on which the kernel counts evaluations.
    type, extends(force_model_t) :: counting_model_t
    contains
        procedure :: acceleration => counting_acceleration
        procedure :: gradient => counting_gradient
        procedure :: has_gradient => counting_has_gradient
    end type counting_model_t

    !> One splitting method: its stages and what is known about it.
    type, public :: scheme_t
        character(len=:), allocatable :: name   !! the paper's label, e.g. `A'`, `M2(-0.5)`
        integer :: order = 0                    !! order of accuracy claimed by the table
        integer :: nop = 0                      !! number of stages
        integer, allocatable :: op(:)           !! operation code of each stage (`OP_*`)
        real(wp), allocatable :: c(:)           !! drift or kick weight of each stage
        real(wp), allocatable :: u(:)           !! gradient weight or extrapolation shift, else 0
        logical :: forward = .false.            !! all drift and kick weights >= 0
        logical :: symplectic = .false.         !! symplectic for every force (no extrapolation)
        logical :: symmetric = .false.          !! palindromic table: time-reversible
        logical :: fsal = .false.               !! first and last stage share their force
        integer :: nforce = 0                   !! force evaluations per step (FSAL counted once)
        integer :: ngrad = 0                    !! gradient evaluations per step
    contains
        procedure :: needs_gradient => scheme_needs_gradient
            !! true when any stage is a gradient kick
        procedure :: extrapolated => scheme_extrapolated
            !! the scheme with extrapolated kicks (A -> A')
        procedure :: describe => scheme_describe        !! one text line per stage
        procedure :: min_drift => scheme_min_drift      !! smallest drift weight
        procedure :: min_kick => scheme_min_kick        !! smallest kick weight
    end type scheme_t

    public :: fsym_scheme_custom, fsym_scheme_extrapolate, fsym_scheme_take
    public :: fsym_op_name, fsym_op_name_len

    !> Width of one line of `scheme_t%describe()` (without its newline).
    integer, parameter :: describe_width = 72

    real(wp), parameter :: consistency_tol = 1.0e-12_wp
    character(len=17), parameter :: op_names(0:4) = [character(len=17) :: 'unknown', &
        'drift', 'kick', 'gradient-kick', 'extrapolated-kick']

contains

    ! ---------------------------------------------------------------- user tables and metadata

    !> Build a scheme from the user's own stage arrays, check it and fill in its metadata.
    !> Rejected (non-zero `stat`, `scheme` untouched) when an op code is unknown, a weight is
    !> not finite, the drift weights or the kick weights do not sum to one, or the table
    !> cannot be allocated (`FSYM_ERR_NO_MEMORY`).
    subroutine fsym_scheme_custom(name, op, c, u, order, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! label of the method
        integer, intent(in) :: op(:)                    !! operation code per stage (`OP_*`)
        real(wp), intent(in) :: c(:)                    !! drift or kick weight per stage
        real(wp), intent(in) :: u(:)                    !! gradient weight / extrapolation shift
        integer, intent(in) :: order                    !! order the table is meant to have
        type(scheme_t), intent(inout) :: scheme         !! the scheme, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        type(scheme_t) :: s
        real(wp) :: sum_drift, sum_kick
        integer :: k, n, ist
        character(len=64) :: buf

        n = size(op)
        if (n < 1 .or. size(c) /= n .or. size(u) /= n) then
            call fsym_report(FSYM_ERR_SHAPE, 'scheme '//trim(name)// &
                             ': op, c and u must have the same non-zero length', stat, errmsg)
            return
        end if
        do k = 1, n
            if (op(k) < OP_DRIFT .or. op(k) > OP_EXTRAP_KICK) then
                write (buf, '(a,i0,a,i0)') 'stage ', k, ' has unknown op code ', op(k)
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                                 trim(buf), stat, errmsg)
                return
            end if
            if (.not. (abs(c(k)) <= huge(1.0_wp) .and. abs(u(k)) <= huge(1.0_wp))) then
                write (buf, '(a,i0,a)') 'stage ', k, ' has a non-finite coefficient'
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                                 trim(buf), stat, errmsg)
                return
            end if
        end do
        sum_drift = sum(c, mask=(op == OP_DRIFT))
        sum_kick = sum(c, mask=(op /= OP_DRIFT))
        if (abs(sum_drift - 1.0_wp) > consistency_tol .or. &
            abs(sum_kick - 1.0_wp) > consistency_tol) then
            write (buf, '(a,es12.5,a,es12.5)') 'drifts sum to ', sum_drift, &
                ', kicks to ', sum_kick
            call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                             trim(buf)//' (both must be 1)', stat, errmsg)
            return
        end if

        allocate (character(len=len_trim(name)) :: s%name, stat=ist)
        if (ist == 0) allocate (s%op(n), stat=ist)
        if (ist == 0) allocate (s%c(n), stat=ist)
        if (ist == 0) allocate (s%u(n), stat=ist)
        if (ist /= 0) then
            write (buf, '(i0)') n
            call fsym_report(FSYM_ERR_NO_MEMORY, 'scheme '//trim(name)//': a table of '// &
                             trim(buf)//' stages', stat, errmsg)
            return
        end if
        s%name(:) = name(1:len_trim(name))
        s%order = order
        s%nop = n
        s%op(:) = op
        s%c(:) = c
        s%u(:) = u
        where (s%op == OP_DRIFT .or. s%op == OP_KICK) s%u = 0.0_wp
        call fill_metadata(s)
        call fsym_scheme_take(s, scheme)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_custom

    !> Move the scheme `from` into `to` without copying its arrays (`from` is left empty).
    !> Constructors build a scheme in a local variable and hand it over with this, so that
    !> the caller's scheme changes only on success and no allocation happens on assignment.
    pure subroutine fsym_scheme_take(from, to)
        type(scheme_t), intent(inout) :: from  !! the scheme to hand over; empty on return
        type(scheme_t), intent(inout) :: to    !! receives it
        call move_alloc(from%name, to%name)
        call move_alloc(from%op, to%op)
        call move_alloc(from%c, to%c)
        call move_alloc(from%u, to%u)
        to%order = from%order
        to%nop = from%nop
        to%forward = from%forward
        to%symplectic = from%symplectic
        to%symmetric = from%symmetric
        to%fsal = from%fsal
        to%nforce = from%nforce
        to%ngrad = from%ngrad
        from%nop = 0
    end subroutine fsym_scheme_take

    !> Metadata that follow from the table alone.
    subroutine fill_metadata(s)
        type(scheme_t), intent(inout) :: s
        integer :: k, n
        n = s%nop
        s%forward = all(s%c >= 0.0_wp)
        s%symplectic = .not. any(s%op == OP_EXTRAP_KICK)
        s%symmetric = .true.
        do k = 1, n / 2
            if (s%op(k) /= s%op(n + 1 - k) .or. &
                abs(s%c(k) - s%c(n + 1 - k)) > 1.0e-14_wp * max(1.0_wp, abs(s%c(k))) .or. &
                abs(s%u(k) - s%u(n + 1 - k)) > 1.0e-14_wp * max(1.0_wp, abs(s%u(k)))) then
                s%symmetric = .false.
            end if
        end do
        s%fsal = s%op(1) /= OP_DRIFT .and. s%op(n) /= OP_DRIFT
        call count_evaluations(s%op, s%c, s%u, s%nforce, s%ngrad)
    end subroutine fill_metadata

    !> Evaluations per step in steady state, counted by the kernel itself: two steps on one
    !> particle of a zero force, the second counted (its cache rules decide, nothing else).
    subroutine count_evaluations(op, c, u, nforce, ngrad)
        integer, intent(in) :: op(:)
        real(wp), intent(in) :: c(:), u(:)
        integer, intent(out) :: nforce, ngrad
        type(counting_model_t) :: model
        type(kernel_state_t) :: ks
        real(wp) :: q(1, 1), v(1, 1), w(1, 1, 12)
        integer(ik) :: nd, nf0, ng0, nf, ng
        integer :: st
        q = 1.0_wp; v = 0.0_wp; w = 0.0_wp
        call fsym_kernel_layout(op, .false., 1, 1, ks)
        nforce = 0; ngrad = 0
        if (fsym_kernel_slots(ks) > size(w, 3)) return
        call fsym_kernel_run(size(op), op, c, u, model, ks, q, v, w, 1.0_wp, 1_ik, nd, st)
        call fsym_kernel_counts(ks, nf0, ng0)
        call fsym_kernel_run(size(op), op, c, u, model, ks, q, v, w, 1.0_wp, 1_ik, nd, st)
        call fsym_kernel_counts(ks, nf, ng)
        nforce = int(nf - nf0); ngrad = int(ng - ng0)
    end subroutine count_evaluations

    subroutine counting_acceleration(self, q, a, stat)
        class(counting_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        associate (u1 => self, u2 => q, u3 => stat); end associate   ! a zero force
        a = 0.0_wp
    end subroutine counting_acceleration

    subroutine counting_gradient(self, q, a, g, stat)
        class(counting_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :), a(:, :)
        real(wp), intent(out), contiguous :: g(:, :)
        integer, intent(inout) :: stat
        associate (u1 => self, u2 => q, u3 => a, u4 => stat); end associate   ! a zero term
        g = 0.0_wp
    end subroutine counting_gradient

    logical function counting_has_gradient(self)
        class(counting_model_t), intent(in) :: self
        associate (unused => self); end associate
        counting_has_gradient = .true.
    end function counting_has_gradient

    !> True when any stage is a gradient kick.
    pure logical function scheme_needs_gradient(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_needs_gradient = .false.
        if (allocated(self%op)) scheme_needs_gradient = any(self%op == OP_GRAD_KICK)
    end function scheme_needs_gradient

    !> The same scheme with every gradient kick v h (a + (u/v) h^2 g) replaced by the
    !> extrapolated kick v h a(q + (2u/v) h^2 a), which agrees to O(h^5) (Chin 2007, the
    !> paper's A'); a prime is added to the name. A scheme without gradient kicks is returned
    !> unchanged. If memory for the copy cannot be had, the result is an empty scheme
    !> (`nop` = 0, nothing allocated); `fsym_scheme_extrapolate` reports that as a status.
    function scheme_extrapolated(self) result(s)
        class(scheme_t), intent(in) :: self  !! the scheme with gradient kicks
        type(scheme_t) :: s
        integer :: st
        call fsym_scheme_extrapolate(self, s, st)
    end function scheme_extrapolated

    !> `to` becomes `from` with every gradient kick replaced by the extrapolated kick and a
    !> prime added to the name (see `scheme_t%extrapolated`); a scheme without gradient kicks
    !> is copied unchanged. `to` is set only on success (`FSYM_ERR_NO_MEMORY` otherwise).
    subroutine fsym_scheme_extrapolate(from, to, stat, errmsg)
        class(scheme_t), intent(in) :: from             !! the scheme with gradient kicks
        type(scheme_t), intent(inout) :: to             !! receives the extrapolated scheme
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        type(scheme_t) :: s
        integer :: k, n, ist, m
        logical :: grad
        n = from%nop
        if (.not. allocated(from%name) .or. .not. allocated(from%op) .or. n < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'extrapolating an empty scheme', stat, errmsg)
            return
        end if
        grad = from%needs_gradient()
        m = len(from%name)
        if (grad) m = m + 1
        allocate (character(len=m) :: s%name, stat=ist)
        if (ist == 0) allocate (s%op(n), stat=ist)
        if (ist == 0) allocate (s%c(n), stat=ist)
        if (ist == 0) allocate (s%u(n), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'scheme '//from%name// &
                             ': no memory for its extrapolated form', stat, errmsg)
            return
        end if
        s%name(1:len(from%name)) = from%name
        s%op(:) = from%op(1:n)
        s%c(:) = from%c(1:n)
        s%u(:) = from%u(1:n)
        s%order = from%order
        s%nop = n
        if (grad) then
            do k = 1, n
                if (s%op(k) == OP_GRAD_KICK) then
                    s%op(k) = OP_EXTRAP_KICK
                    s%u(k) = 2.0_wp * from%u(k) / from%c(k)
                end if
            end do
            s%name(m:m) = ''''
        end if
        call fill_metadata(s)
        call fsym_scheme_take(s, to)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_extrapolate

    !> Most negative (or smallest) drift weight: how far the method steps backward in position.
    pure real(wp) function scheme_min_drift(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_min_drift = minval(self%c, mask=(self%op == OP_DRIFT))
    end function scheme_min_drift

    !> Smallest kick weight.
    pure real(wp) function scheme_min_kick(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_min_kick = minval(self%c, mask=(self%op /= OP_DRIFT))
    end function scheme_min_kick

    !> Length of `fsym_op_name(op)` (a specification function, so that the name has an exact
    !> length without a deferred-length result).
    pure integer function fsym_op_name_len(op)
        integer, intent(in) :: op  !! an `OP_*` code
        fsym_op_name_len = len_trim(op_names(op_index(op)))
    end function fsym_op_name_len

    !> Name of an operation code: `drift`, `kick`, `gradient-kick`, `extrapolated-kick`, or
    !> `unknown`.
    pure function fsym_op_name(op) result(name)
        integer, intent(in) :: op  !! an `OP_*` code
        character(len=fsym_op_name_len(op)) :: name
        name = op_names(op_index(op))
    end function fsym_op_name

    !> Index of `op` in `op_names` (0 for an unknown code).
    pure integer function op_index(op)
        integer, intent(in) :: op
        op_index = 0
        if (op >= OP_DRIFT .and. op <= OP_EXTRAP_KICK) op_index = op
    end function op_index

    !> One line per stage (`describe_width` characters and a newline): stage number, op name,
    !> weight c and second coefficient u.
    function scheme_describe(self) result(text)
        class(scheme_t), intent(in) :: self  !! the scheme
        character(len=max(self%nop, 0) * (describe_width + 1)) :: text
        integer :: k, p
        text = ''
        do k = 1, self%nop
            p = (k - 1) * (describe_width + 1)
            write (text(p + 1:p + describe_width), '(i3,1x,a18,2(1x,es24.16))') k, &
                fsym_op_name(self%op(k)), self%c(k), self%u(k)
            text(p + describe_width + 1:p + describe_width + 1) = new_line('a')
        end do
    end function scheme_describe

end module fsym_scheme
