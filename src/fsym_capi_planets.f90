!> C face of the planetary drop-in (`include/fsym.h`, `fsym_planets_*`): the same work image
!> and the same procedures as the F77 routines FSYMPW ... FSYMPE (`fsym_legacy_planets`), so
!> the three faces give the same bits. The work arrays are the caller's `double rw[lrw]` and
!> `int iw[liw]`; positions and velocities are `double x[n][3]` (Fortran x(3, n)),
!> heliocentric. Every function returns a status; NULL pointers give FSYM_ERR_BAD_ARGUMENT.
module fsym_capi_planets
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_funptr, &
                                           c_null_char, c_associated, c_f_pointer, &
                                           c_f_procpointer
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT
    use fsym_force, only: force_model_t
    use fsym_legacy_planets, only: pl_sizes, pl_setup, pl_steps, pl_state, pl_message, &
                                   pl_energy, PL_LABEL_MAX, PL_MSG_LEN
    implicit none
    private

    public :: fsym_c_planets_work_size, fsym_c_planets_init, fsym_c_planets_step
    public :: fsym_c_planets_state, fsym_c_planets_message, fsym_c_planets_energy

    abstract interface
        !> C extra force: `int force(int n, const double *x, double *a, void *user)`,
        !> accelerations a[n][3] at the heliocentric x[n][3]; non-zero return = failure.
        integer(c_int) function c_pl_force_iface(n, x, a, user) bind(C)
            import :: c_int, c_double, c_ptr
            implicit none
            integer(c_int), value :: n
            real(c_double), intent(in) :: x(*)
            real(c_double), intent(out) :: a(*)
            type(c_ptr), value :: user
        end function c_pl_force_iface
    end interface

    !> The C caller's extra force with its user data.
    type, extends(force_model_t) :: c_pl_force_t
        type(c_funptr) :: f
        type(c_ptr) :: user
    contains
        procedure :: acceleration => c_pl_acceleration
    end type c_pl_force_t

contains

    subroutine c_pl_acceleration(self, q, a, stat)
        class(c_pl_force_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        procedure(c_pl_force_iface), pointer :: f
        call c_f_procpointer(self%f, f)
        stat = int(f(int(size(q, 2), c_int), q, a, self%user))
    end subroutine c_pl_acceleration

    !> The NUL-terminated label at `method` (false: NULL, or longer than PL_LABEL_MAX).
    logical function c_label(method, name, nlen)
        type(c_ptr), intent(in) :: method
        character(len=PL_LABEL_MAX), intent(out) :: name
        integer, intent(out) :: nlen
        character(kind=c_char), pointer :: chars(:)
        integer :: k
        name = ''; nlen = -1
        c_label = .false.
        if (.not. c_associated(method)) return
        call c_f_pointer(method, chars, [PL_LABEL_MAX + 1])
        do k = 1, PL_LABEL_MAX + 1
            if (chars(k) == c_null_char) then
                nlen = k - 1; exit
            end if
            if (k <= PL_LABEL_MAX) name(k:k) = chars(k)
        end do
        c_label = nlen >= 0
    end function c_label

    !> `int fsym_planets_work_size(const char *method, int n, int *lrw, int *liw)`: the work
    !> sizes (as FSYMPW).
    integer(c_int) function fsym_c_planets_work_size(method, n, lrw, liw) &
        bind(C, name='fsym_planets_work_size') result(stat)
        type(c_ptr), value :: method          !! method label
        integer(c_int), value :: n            !! bodies besides the centre
        type(c_ptr), value :: lrw, liw        !! int *: the lengths
        integer(c_int), pointer :: r, i
        character(len=PL_LABEL_MAX) :: name
        character(len=PL_MSG_LEN) :: msg
        integer :: nlen, st, a, b
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(lrw) .and. c_associated(liw))) return
        if (.not. c_label(method, name, nlen)) return
        call pl_sizes(name(1:nlen), int(n), a, b, st, msg)
        call c_f_pointer(lrw, r); call c_f_pointer(liw, i)
        r = int(a, c_int); i = int(b, c_int)
        stat = int(st, c_int)
    end function fsym_c_planets_work_size

    !> `int fsym_planets_init(const char *method, int coords, int n, double m0,
    !> const double *m, double g, double hill, double *rw, int lrw, int *iw, int liw)`: set up
    !> the work arrays (as FSYMPI; coords 1 Jacobi, 2 democratic, 3 Jacobi with M_k = eta_k).
    integer(c_int) function fsym_c_planets_init(method, coords, n, m0, m, g, hill, rw, lrw, &
                                                iw, liw) bind(C, name='fsym_planets_init') &
        result(stat)
        type(c_ptr), value :: method          !! method label
        integer(c_int), value :: coords, n    !! coordinates, bodies
        real(c_double), value :: m0, g, hill  !! central mass, G, encounter radius
        type(c_ptr), value :: m               !! const double m[n]
        type(c_ptr), value :: rw, iw          !! work arrays
        integer(c_int), value :: lrw, liw     !! their lengths
        real(wp), pointer, contiguous :: mf(:), rf(:)
        integer(c_int), pointer, contiguous :: jf(:)
        character(len=PL_LABEL_MAX) :: name
        character(len=PL_MSG_LEN) :: msg
        integer :: nlen, st
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(m) .and. c_associated(rw) .and. c_associated(iw))) return
        if (n < 1 .or. lrw < 1 .or. liw < 1) return
        if (.not. c_label(method, name, nlen)) return
        call c_f_pointer(m, mf, [n]); call c_f_pointer(rw, rf, [lrw])
        call c_f_pointer(iw, jf, [liw])
        call pl_setup(name(1:nlen), int(coords), int(n), m0, mf, g, hill, rf, int(lrw), jf, &
                      int(liw), st, msg)
        stat = int(st, c_int)
    end function fsym_c_planets_init

    !> `int fsym_planets_step(int n, double m0, const double *m, double g, double *x,
    !> double *v, double h, int nstep, fsym_planets_force_fn force, void *user,
    !> double fraction, double *rw, int lrw, int *iw, int liw)`: nstep steps (as FSYMPU;
    !> force may be NULL; fraction > 0 turns the guard on).
    integer(c_int) function fsym_c_planets_step(n, m0, m, g, x, v, h, nstep, force, user, &
                                                fraction, rw, lrw, iw, liw) &
        bind(C, name='fsym_planets_step') result(stat)
        integer(c_int), value :: n, nstep     !! bodies, steps
        real(c_double), value :: m0, g, h     !! central mass, G, step
        real(c_double), value :: fraction     !! guard (<= 0: off)
        type(c_ptr), value :: m, x, v         !! masses, heliocentric state
        type(c_funptr), value :: force        !! extra force or NULL
        type(c_ptr), value :: user            !! passed to force
        type(c_ptr), value :: rw, iw          !! work arrays
        integer(c_int), value :: lrw, liw     !! their lengths
        real(wp), pointer, contiguous :: mf(:), rf(:), xf(:, :), vf(:, :)
        integer(c_int), pointer, contiguous :: jf(:)
        type(c_pl_force_t) :: extra
        character(len=PL_MSG_LEN) :: msg
        integer :: st
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(m) .and. c_associated(rw) .and. c_associated(iw) .and. &
                   c_associated(x) .and. c_associated(v))) return
        if (n < 1 .or. lrw < 1 .or. liw < 1) return
        call c_f_pointer(m, mf, [n]); call c_f_pointer(rw, rf, [lrw])
        call c_f_pointer(iw, jf, [liw])
        call c_f_pointer(x, xf, [3, n]); call c_f_pointer(v, vf, [3, n])
        if (c_associated(force)) then
            extra%f = force; extra%user = user
            call pl_steps(int(n), m0, mf, g, xf, vf, h, int(nstep), rf, int(lrw), jf, int(liw), &
                          st, msg, extra, fraction)
        else
            call pl_steps(int(n), m0, mf, g, xf, vf, h, int(nstep), rf, int(lrw), jf, int(liw), &
                          st, msg, frac=fraction)
        end if
        stat = int(st, c_int)
    end function fsym_c_planets_step

    !> `int fsym_planets_state(int n, double *x, double *v, const double *rw, int lrw,
    !> const int *iw, int liw)`: the heliocentric state kept in the work arrays (as FSYMPX).
    integer(c_int) function fsym_c_planets_state(n, x, v, rw, lrw, iw, liw) &
        bind(C, name='fsym_planets_state') result(stat)
        integer(c_int), value :: n            !! bodies
        type(c_ptr), value :: x, v            !! receive the state
        type(c_ptr), value :: rw, iw          !! work arrays
        integer(c_int), value :: lrw, liw     !! their lengths
        real(wp), pointer, contiguous :: rf(:), xf(:, :), vf(:, :)
        integer(c_int), pointer, contiguous :: jf(:)
        integer :: st
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(rw) .and. c_associated(iw) .and. c_associated(x) .and. &
                   c_associated(v))) return
        if (n < 1 .or. lrw < 1 .or. liw < 1) return
        call c_f_pointer(rw, rf, [lrw]); call c_f_pointer(iw, jf, [liw])
        call c_f_pointer(x, xf, [3, n]); call c_f_pointer(v, vf, [3, n])
        call pl_state(int(n), xf, vf, rf, int(lrw), jf, int(liw), st)
        stat = int(st, c_int)
    end function fsym_c_planets_state

    !> `int fsym_planets_message(int status, const double *rw, int lrw, const int *iw,
    !> int liw, char *buf, int len)`: the message of the status the last call returned (as
    !> FSYMPM), NUL-terminated in buf.
    integer(c_int) function fsym_c_planets_message(status, rw, lrw, iw, liw, buf, buflen) &
        bind(C, name='fsym_planets_message') result(stat)
        integer(c_int), value :: status       !! the status returned
        type(c_ptr), value :: rw, iw          !! work arrays
        integer(c_int), value :: lrw, liw     !! their lengths
        type(c_ptr), value :: buf             !! receives the text
        integer(c_int), value :: buflen       !! size of buf in bytes
        real(wp), pointer, contiguous :: rf(:)
        integer(c_int), pointer, contiguous :: jf(:)
        character(kind=c_char), pointer :: b(:)
        character(len=PL_MSG_LEN) :: msg
        integer :: k, mlen
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(rw) .and. c_associated(iw) .and. c_associated(buf))) return
        if (lrw < 1 .or. liw < 1 .or. buflen < 1) return
        call c_f_pointer(rw, rf, [lrw]); call c_f_pointer(iw, jf, [liw])
        msg = ''
        call pl_message(int(status), rf, int(lrw), jf, int(liw), msg)
        call c_f_pointer(buf, b, [buflen])
        mlen = min(len_trim(msg), int(buflen) - 1)
        do k = 1, mlen
            b(k) = msg(k:k)
        end do
        b(mlen + 1) = c_null_char
        stat = FSYM_SUCCESS
    end function fsym_c_planets_message

    !> `int fsym_planets_energy(int n, double m0, const double *m, double g, const double *x,
    !> const double *v, double *e)`: total energy of a heliocentric state (as FSYMPE).
    integer(c_int) function fsym_c_planets_energy(n, m0, m, g, x, v, e) &
        bind(C, name='fsym_planets_energy') result(stat)
        integer(c_int), value :: n            !! bodies
        real(c_double), value :: m0, g        !! central mass, G
        type(c_ptr), value :: m, x, v         !! masses, heliocentric state
        type(c_ptr), value :: e               !! double *: the energy
        real(wp), pointer, contiguous :: mf(:), xf(:, :), vf(:, :)
        real(wp), pointer :: ef
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(m) .and. c_associated(x) .and. c_associated(v) .and. &
                   c_associated(e)) .or. n < 1) return
        call c_f_pointer(m, mf, [n]); call c_f_pointer(e, ef)
        call c_f_pointer(x, xf, [3, n]); call c_f_pointer(v, vf, [3, n])
        call pl_energy(int(n), m0, mf, g, xf, vf, ef)
        stat = FSYM_SUCCESS
    end function fsym_c_planets_energy

end module fsym_capi_planets
