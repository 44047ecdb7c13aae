!> The one place where a splitting table of the library (`scheme_t`: op codes and the
!> coefficient arrays c and u, see `fsym_scheme`) becomes a sequence of grid factors for the
!> imaginary-time Schroedinger equation d psi/d tau = (1/2 lap - V) psi = -(T + V) psi.
!>
!> **Derivation.** A table is a formal identity between exponentials of two operators A and B:
!> its stages multiply e^{c h A} (drift) and e^{c h (B + w h^2 [B,[A,B]])} (gradient kick with
!> w = u/c), and the product equals e^{h(A+B)} up to h^{p+1}. The classical kernel reads it
!> with the Lie operators A = {.,T}, B = {.,V} of T = p^2/2: e^{hB} is p <- p - h grad V, and
!> since {V,{T,V}} = -|grad V|^2, the gradient kick is the kick of the potential
!> c V - u h^2 |grad V|^2, i.e. p <- p + c h F + u h^3 grad|F|^2 with F = -grad V: the
!> convention of the tables (METHODS.md, "Conventions"). Imaginary time reads the same
!> identity with A = -T = lap/2, B = -V and h = tau; now [B,[A,B]] = -[V,[T,V]] = -|grad V|^2
!> (for T = -lap/2, [V,[T,V]] = |grad V|^2 exactly), so the stages become
!>
!> * drift (c)              psi <- F^-1 exp(-c tau |k|^2/2) F psi       (kinetic factor)
!> * kick (c)               psi <- exp(-c tau V) psi
!> * gradient kick (c, u)   psi <- exp(-tau (c V + u tau^2 |grad V|^2)) psi
!>
!> with the table's own c and u: the sign of the |grad V|^2 term is + here where the classical
!> potential has -, and no other factor enters. Running the stages in table order multiplies
!> the factors in the reverse order of the operator product; the reversed product approximates
!> e^{-tau H} to the same order, since reversal maps [B,[A,B]] to itself. A wrong sign of the
!> gradient term leaves a method of order 2 (the tests measure 4).
!>
!> **Forward only.** A drift with c < 0 is exp(+|c| tau |k|^2/2): backward diffusion, unbounded
!> in k (Sheng 1989, Suzuki 1991; Chin 2007, the paper's first argument for forward methods):
!> such a table is refused. Negative kick weights are bounded on a grid and allowed.
!>
!> **Extrapolated kicks (A')** replace the gradient term by a force at a shifted point,
!> F(q + s h^2 F). On the grid the analogue would be c V(x + (s/2) tau^2 grad V(x)), which
!> equals c V + u tau^2 |grad V|^2 + O(tau^4) (u = c s/2); it needs V off the grid points,
!> which an array V (or a Gross-Pitaevskii density) does not give, and it needs grad V, from
!> which |grad V|^2 is as cheap. So A' saves nothing here and is refused with a status
!> (use A: its gradient term costs no FFT for a fixed V).
!>
!> **Merged stages.** Consecutive stages of the same kind are merged when a table becomes
!> grid stages (two kinetic factors commute and multiply; two potential factors add their
!> weights), so a table written as a repeated step pays one drift's two FFTs per merged run.
!> The propagator (`fsym_itp`) also merges the last drift of a step with the first of the
!> next when a table starts and ends with drifts (`TVT`, `B`, `C`), by holding the spectra
!> of the states between steps: 2 (n_drift - 1) FFTs a step.
!>
!> **Multi-product expansions** (`MPq`, `BASE-MPq`): sum_i w_i S(tau/i)^i of a symmetric
!> forward base S (Strang by default, or A, B, ...), every sub-step forward; the weights
!> alternate in sign (`fsym_itp_mp_weights`). The branches are concatenated in one stage
!> list, each branch's stages with weights c/i (and u/i^3), and run from the same state.
!>
!> Two methods are not tables: `Strang` is the table V/2 T V/2 (built with
!> `fsym_scheme_custom`: one drift, two FFTs per step), and `CN` is the first-order split-step
!> Crank-Nicolson of the published Gross-Pitaevskii codes, psi <- C(tau) exp(-tau V) psi with
!> the Cayley factor C = (1 - tau |k|^2/4)/(1 + tau |k|^2/4) applied in Fourier space (spectral
!> in x, so that only its time discretisation differs from the others).
module fsym_itp_stages
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_INCONSISTENT_SCHEME, &
                           FSYM_ERR_NO_MEMORY, fsym_report, fsym_pass
    use fsym_scheme, only: scheme_t, fsym_scheme_custom, OP_DRIFT, OP_KICK, OP_GRAD_KICK, &
                           OP_EXTRAP_KICK
    use fsym_paper_schemes, only: fsym_scheme_by_name
    implicit none
    private

    integer, parameter, public :: ITP_KINETIC = 1    !! exp(-c tau |k|^2/2) in Fourier space
    integer, parameter, public :: ITP_POTENTIAL = 2  !! exp(-tau (c V + u tau^2 |grad V|^2))
    integer, parameter, public :: ITP_CAYLEY = 3     !! (1 - tau|k|^2/4)/(1 + tau|k|^2/4)
    integer, parameter, public :: ITP_NAME_LEN = 24  !! length of a method name

    !> One grid stage: what it applies and with which weights.
    type, public :: fsym_itp_stage_t
        integer :: kind = 0           !! `ITP_KINETIC`, `ITP_POTENTIAL` or `ITP_CAYLEY`
        real(wp) :: c = 0.0_wp        !! weight of T (kinetic) or of V (potential)
        real(wp) :: u = 0.0_wp        !! weight of tau^2 |grad V|^2 (potential only)
    end type fsym_itp_stage_t

    public :: fsym_itp_stages_from_scheme, fsym_itp_method, fsym_itp_mp_weights
    public :: fsym_itp_kinetic_exponent, fsym_itp_potential_exponent, fsym_itp_cayley

contains

    !> Grid stages of a library table (see the module text for the map); refused
    !> (`FSYM_ERR_INCONSISTENT_SCHEME`, `stages` untouched) for a negative drift weight or an
    !> extrapolated kick.
    subroutine fsym_itp_stages_from_scheme(scheme, stages, stat, errmsg)
        type(scheme_t), intent(in) :: scheme                        !! the table
        type(fsym_itp_stage_t), allocatable, intent(inout) :: stages(:)  !! its grid stages
        integer, intent(out), optional :: stat                      !! status code
        character(len=*), intent(inout), optional :: errmsg         !! message on error
        type(fsym_itp_stage_t), allocatable :: raw(:)
        integer :: k
        character(len=16) :: buf
        do k = 1, scheme%nop
            write (buf, '(i0)') k
            if (scheme%op(k) == OP_DRIFT .and. scheme%c(k) < 0.0_wp) then
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: '// &
                                 scheme%name//' has a negative drift weight at stage '// &
                                 trim(buf)//' (backward diffusion, unbounded; only forward '// &
                                 'methods apply)', stat, errmsg)
                return
            end if
            if (scheme%op(k) == OP_EXTRAP_KICK) then
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: '// &
                                 scheme%name//' extrapolates its kick (stage '//trim(buf)// &
                                 '): V off the grid is not available, use the gradient form', &
                                 stat, errmsg)
                return
            end if
        end do
        allocate (raw(scheme%nop), stat=k)
        if (k /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'imaginary time: stage table', stat, errmsg)
            return
        end if
        do k = 1, scheme%nop
            select case (scheme%op(k))
            case (OP_DRIFT)
                raw(k) = fsym_itp_stage_t(ITP_KINETIC, scheme%c(k), 0.0_wp)
            case (OP_KICK)
                raw(k) = fsym_itp_stage_t(ITP_POTENTIAL, scheme%c(k), 0.0_wp)
            case (OP_GRAD_KICK)
                raw(k) = fsym_itp_stage_t(ITP_POTENTIAL, scheme%c(k), scheme%u(k))
            case default
                ! op codes are validated when a scheme is built
            end select
        end do
        if (allocated(stages)) deallocate (stages)
        stages = merged(raw)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_itp_stages_from_scheme

    !> The stages with every run of consecutive stages of the same kind merged into one:
    !> two kinetic factors multiply to one of weight c1 + c2 (they commute), two potential
    !> factors to one of weights (c1 + c2, u1 + u2); exact, and it saves the two FFTs of a
    !> drift (tables written as a step repeated, multi-product branches).
    pure function merged(raw) result(out)
        type(fsym_itp_stage_t), intent(in) :: raw(:)   !! stages in table order
        type(fsym_itp_stage_t), allocatable :: out(:)  !! the same product, runs merged
        type(fsym_itp_stage_t) :: tmp(size(raw))
        integer :: k, m
        m = 0
        do k = 1, size(raw)
            if (m > 0) then
                if (tmp(m)%kind == raw(k)%kind .and. raw(k)%kind /= ITP_CAYLEY) then
                    tmp(m)%c = tmp(m)%c + raw(k)%c
                    tmp(m)%u = tmp(m)%u + raw(k)%u
                    cycle
                end if
            end if
            m = m + 1
            tmp(m) = raw(k)
        end do
        out = tmp(1:m)
    end function merged

    !> Grid stages of a method label: `CN` (split-step Crank-Nicolson, order 1), `Strang`
    !> (V/2 T V/2, order 2), `TVT` (T/2 V T/2, order 2), `B` (Chin's forward B, order 4),
    !> any label of `fsym_scheme_by_name` (A, C, A4, A5, ...), or a
    !> multi-product expansion `MPq` (of Strang) or `BASE-MPq` (of a symmetric table BASE of
    !> even order p < q, e.g. `A-MP6`): the sum over branches i = 1..n, n = (q - p)/2 + 1, of
    !> w_i S(tau/i)^i (see `fsym_itp_mp_weights`). The stages of all branches are concatenated;
    !> branch i runs stages `branch_first(i)` to `branch_first(i+1) - 1` and carries weight
    !> `branch_weight(i)` (one branch of weight 1 for a single table). A multi-product label
    !> without the branch arguments is refused.
    subroutine fsym_itp_method(label, stages, order, name, stat, errmsg, branch_first, &
                               branch_weight)
        character(len=*), intent(in) :: label                       !! method label
        type(fsym_itp_stage_t), allocatable, intent(inout) :: stages(:)  !! its grid stages
        integer, intent(out) :: order                               !! its order in tau
        character(len=ITP_NAME_LEN), intent(out) :: name            !! its name
        integer, intent(out), optional :: stat                      !! status code
        character(len=*), intent(inout), optional :: errmsg         !! message on error
        integer, allocatable, intent(inout), optional :: branch_first(:)  !! first stage of
                                                                    !! each branch, then nst+1
        real(wp), allocatable, intent(inout), optional :: branch_weight(:)  !! branch weights
        type(scheme_t) :: s
        type(fsym_itp_stage_t), allocatable :: base(:), rep(:), all(:)
        integer :: st, imp, q, nb, i, j, nfirst(16)
        real(wp) :: w(16)
        character(len=256) :: msg
        character(len=64) :: key, basekey
        name = adjustl(label)
        key = lower(trim(adjustl(label)))
        if (key == 'cn') then
            if (allocated(stages)) deallocate (stages)
            stages = [fsym_itp_stage_t(ITP_POTENTIAL, 1.0_wp, 0.0_wp), &
                      fsym_itp_stage_t(ITP_CAYLEY, 1.0_wp, 0.0_wp)]
            order = 1
            name = 'CN'
            call one_branch(size(stages), branch_first, branch_weight)
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        ! multi-product label: [BASE-]MPq
        q = 0
        basekey = key
        imp = index(key, 'mp', back=.true.)
        if (imp > 0) then
            if (imp == 1 .or. key(max(imp - 1, 1):max(imp - 1, 1)) == '-') then
                if (verify(trim(key(imp + 2:)), '0123456789') == 0 .and. &
                    len_trim(key(imp + 2:)) > 0 .and. len_trim(key(imp + 2:)) <= 2) then
                    read (key(imp + 2:), *) q
                    basekey = 'strang'
                    if (imp > 2) basekey = key(1:imp - 2)
                end if
            end if
        end if
        msg = ''
        if (basekey == 'strang') then
            call fsym_scheme_custom('Strang', [OP_KICK, OP_DRIFT, OP_KICK], &
                                    [0.5_wp, 1.0_wp, 0.5_wp], [0.0_wp, 0.0_wp, 0.0_wp], 2, &
                                    s, st, msg)
        else if (basekey == 'tvt') then
            call fsym_scheme_custom('TVT', [OP_DRIFT, OP_KICK, OP_DRIFT], &
                                    [0.5_wp, 1.0_wp, 0.5_wp], [0.0_wp, 0.0_wp, 0.0_wp], 2, &
                                    s, st, msg)
        else if (basekey == 'b') then
            ! Chin's forward algorithm B (S. A. Chin, Phys. Lett. A 226, 344-348 (1997)):
            ! drifts a, 1 - 2a, a with a = (1 - 1/sqrt 3)/2, two gradient kicks 1/2 with
            ! gradient weight (2 - sqrt 3)/48 each
            call fsym_scheme_custom('B', [OP_DRIFT, OP_GRAD_KICK, OP_DRIFT, OP_GRAD_KICK, &
                                    OP_DRIFT], [0.5_wp * (1.0_wp - 1.0_wp / sqrt(3.0_wp)), &
                                    0.5_wp, 1.0_wp / sqrt(3.0_wp), 0.5_wp, &
                                    0.5_wp * (1.0_wp - 1.0_wp / sqrt(3.0_wp))], &
                                    [0.0_wp, (2.0_wp - sqrt(3.0_wp)) / 48.0_wp, 0.0_wp, &
                                    (2.0_wp - sqrt(3.0_wp)) / 48.0_wp, 0.0_wp], 4, s, st, msg)
        else if (q > 0) then
            call fsym_scheme_by_name(label(1:index(lower(label), '-mp', back=.true.) - 1), s, &
                                     st, msg)
        else
            call fsym_scheme_by_name(label, s, st, msg)
        end if
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        call fsym_itp_stages_from_scheme(s, base, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        if (q == 0) then
            if (allocated(stages)) deallocate (stages)
            call move_alloc(base, stages)
            order = s%order
            name = s%name
            call one_branch(size(stages), branch_first, branch_weight)
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        nb = (q - s%order) / 2 + 1
        if (mod(s%order, 2) /= 0 .or. mod(q, 2) /= 0 .or. nb < 2 .or. nb > 6 .or. &
            .not. palindrome(base)) then
            call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: a multi-'// &
                             'product MPq needs a symmetric base of even order p and an even '// &
                             'q with p < q <= p + 10 ('//trim(label)//')', stat, errmsg)
            return
        end if
        if (.not. (present(branch_first) .and. present(branch_weight))) then
            call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: '//trim(label)// &
                             ' is a multi-product expansion, the caller must take its '// &
                             'branches', stat, errmsg)
            return
        end if
        w(1:nb) = fsym_itp_mp_weights(s%order, nb)
        allocate (all(0))
        nfirst(1) = 1
        do i = 1, nb
            ! branch i: the base at tau/i, i times (drift and kick weights / i, gradient / i^3)
            rep = [(base, j = 1, i)]
            rep(:)%c = rep(:)%c / i
            rep(:)%u = rep(:)%u / real(i, wp)**3
            rep = merged(rep)
            all = [all, rep]
            nfirst(i + 1) = size(all) + 1
        end do
        if (allocated(stages)) deallocate (stages)
        call move_alloc(all, stages)
        branch_first = nfirst(1:nb + 1)
        branch_weight = w(1:nb)
        order = q
        name = trim(s%name)//'-MP'//trim(key(imp + 2:))
        if (basekey == 'strang') name = 'MP'//trim(key(imp + 2:))
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_itp_method

    !> Weights of the multi-product expansion of a symmetric method S of even order p with
    !> n branches S(tau/i)^i, i = 1..n (S. A. Chin, Multi-product splitting and Runge-Kutta-
    !> Nystrom integrators, Celest. Mech. Dyn. Astron. 106, 391-406 (2010); S. A. Chin and
    !> J. Geiser, Multi-product operator splitting as a general method of solving autonomous
    !> and nonautonomous equations, IMA J. Numer. Anal. 31, 1552-1577 (2011)). S(tau/i)^i =
    !> exp(tau H + sum_j (tau^(2j+1)/i^(2j)) E_(2j+1)) for S symmetric, and every term of its
    !> expansion at tau^m beyond tau H carries i^(-2j) with 2j >= p; the weights solve
    !> sum_i w_i = 1 and sum_i w_i i^(-2j) = 0 for 2j = p, p + 2, ..., p + 2n - 4, which
    !> removes every error term below tau^(p+2n-1): order p + 2n - 2. For p = 2 this is
    !> w_i = prod_(j /= i) i^2/(i^2 - j^2) (1/24, -16/15, 81/40 for n = 3). Every sub-step is
    !> forward (positive); the weights alternate in sign.
    pure function fsym_itp_mp_weights(p, n) result(w)
        integer, intent(in) :: p          !! order of the symmetric base (even)
        integer, intent(in) :: n          !! number of branches (2..6)
        real(wp) :: w(n)                  !! weight of branch i
        real(wp) :: a(n, n + 1), f, t(n + 1)
        integer :: i, r, piv
        do i = 1, n
            a(1, i) = 1.0_wp
            do r = 2, n
                a(r, i) = (1.0_wp / real(i, wp)**2)**(p / 2 + r - 2)
            end do
        end do
        a(:, n + 1) = 0.0_wp
        a(1, n + 1) = 1.0_wp
        do r = 1, n   ! Gauss-Jordan elimination with partial pivoting
            piv = r - 1 + maxloc(abs(a(r:n, r)), dim=1)
            t = a(r, :); a(r, :) = a(piv, :); a(piv, :) = t
            a(r, :) = a(r, :) / a(r, r)
            do i = 1, n
                if (i == r) cycle
                f = a(i, r)
                a(i, :) = a(i, :) - f * a(r, :)
            end do
        end do
        w = a(:, n + 1)
    end function fsym_itp_mp_weights

    !> One branch of weight 1 holding all `nst` stages (when the caller takes branches).
    subroutine one_branch(nst, branch_first, branch_weight)
        integer, intent(in) :: nst
        integer, allocatable, intent(inout), optional :: branch_first(:)
        real(wp), allocatable, intent(inout), optional :: branch_weight(:)
        if (present(branch_first)) branch_first = [1, nst + 1]
        if (present(branch_weight)) branch_weight = [1.0_wp]
    end subroutine one_branch

    !> Is the stage list its own reverse (a symmetric method)?
    pure logical function palindrome(st)
        type(fsym_itp_stage_t), intent(in) :: st(:)
        integer :: k, n
        n = size(st)
        palindrome = .true.
        do k = 1, n / 2
            palindrome = palindrome .and. st(k)%kind == st(n + 1 - k)%kind .and. &
                         abs(st(k)%c - st(n + 1 - k)%c) <= 1.0e-14_wp .and. &
                         abs(st(k)%u - st(n + 1 - k)%u) <= 1.0e-14_wp
        end do
    end function palindrome

    !> Exponent of the kinetic factor of a drift of weight c: -c tau |k|^2/2.
    pure elemental real(wp) function fsym_itp_kinetic_exponent(c, tau, k2) result(e)
        real(wp), intent(in) :: c      !! drift weight
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: k2     !! |k|^2
        e = -c * tau * 0.5_wp * k2
    end function fsym_itp_kinetic_exponent

    !> Exponent of the potential factor of a (gradient) kick: -tau (c V + u tau^2 |grad V|^2).
    pure elemental real(wp) function fsym_itp_potential_exponent(c, u, tau, v, gsq) result(e)
        real(wp), intent(in) :: c      !! kick weight
        real(wp), intent(in) :: u      !! gradient weight (0 for a plain kick)
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: v      !! potential
        real(wp), intent(in) :: gsq    !! |grad V|^2
        e = -tau * (c * v + u * tau * tau * gsq)
    end function fsym_itp_potential_exponent

    !> The Crank-Nicolson (Cayley) kinetic factor (1 - tau |k|^2/4)/(1 + tau |k|^2/4).
    pure elemental real(wp) function fsym_itp_cayley(tau, k2) result(f)
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: k2     !! |k|^2
        f = (1.0_wp - 0.25_wp * tau * k2) / (1.0_wp + 0.25_wp * tau * k2)
    end function fsym_itp_cayley

    pure function lower(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: i
        t = s
        do i = 1, len(s)
            if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
        end do
    end function lower

end module fsym_itp_stages
