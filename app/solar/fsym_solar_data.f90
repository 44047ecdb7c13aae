!> Reader of the outer-solar-system data file (`data/outer_solar_system.txt`): G, the end
!> time, and for each body its name, mass, initial state and reference state at the end time.
!> Lines starting with `#` are comments; the sections come in the order G, t_end, initial
!> bodies (name m x y z vx vy vz), reference bodies (name x y z vx vy vz).
module fsym_solar_data
    use fsym_kinds, only: wp
    use fsym_status
    implicit none
    private

    integer, parameter :: max_bodies = 64

    !> The contents of the file.
    type, public :: solar_data_t
        real(wp) :: g = 0.0_wp                      !! gravitational constant
        real(wp) :: t_end = 0.0_wp                  !! time of the reference state
        integer :: n = 0                            !! number of bodies
        character(len=16), allocatable :: name(:)   !! body names
        real(wp), allocatable :: m(:)               !! masses
        real(wp), allocatable :: q0(:, :), v0(:, :) !! initial state (3, n)
        real(wp), allocatable :: qref(:, :), vref(:, :)  !! reference state at t_end (3, n)
    end type solar_data_t

    public :: read_solar_data

contains

    !> Read `path` into `dat`; errors (missing file, bad line, body lists that do not match)
    !> are returned with FSYM_ERR_IO.
    subroutine read_solar_data(path, dat, stat, errmsg)
        character(len=*), intent(in) :: path                !! data file
        type(solar_data_t), intent(out) :: dat              !! contents
        integer, intent(out) :: stat                        !! status
        character(len=*), intent(inout) :: errmsg           !! message on error
        character(len=512) :: line
        character(len=16) :: nm(max_bodies), nref(max_bodies)
        real(wp) :: m(max_bodies), s0(6, max_bodies), sref(6, max_bodies)
        integer :: u, ios, section, n0, nr, lineno
        open (newunit=u, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) then
            call fsym_report(FSYM_ERR_IO, 'cannot open '//trim(path), stat, errmsg); return
        end if
        section = 0; n0 = 0; nr = 0; lineno = 0
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            lineno = lineno + 1
            line = adjustl(line)
            if (len_trim(line) == 0) cycle
            if (line(1:1) == '#') then
                ! a comment starting a body list moves on to the next section
                if (index(line, '(initial state') > 0) section = 3
                if (index(line, '(reference state') > 0) section = 4
                cycle
            end if
            select case (section)
            case (0)
                read (line, *, iostat=ios) dat%g
                section = 1
            case (1)
                read (line, *, iostat=ios) dat%t_end
                section = 2
            case (3)
                if (n0 == max_bodies) ios = 1
                if (ios == 0) then
                    n0 = n0 + 1
                    read (line, *, iostat=ios) nm(n0), m(n0), s0(:, n0)
                end if
            case (4)
                if (nr == max_bodies) ios = 1
                if (ios == 0) then
                    nr = nr + 1
                    read (line, *, iostat=ios) nref(nr), sref(:, nr)
                end if
            case default
                ios = 1
            end select
            if (ios /= 0) then
                close (u)
                call fsym_report(FSYM_ERR_IO, trim(path)//': cannot read line '// &
                                 fsym_int_text(lineno), stat, errmsg)
                return
            end if
        end do
        close (u)
        if (n0 < 2 .or. nr /= n0 .or. .not. (dat%g > 0.0_wp .and. dat%t_end > 0.0_wp)) then
            call fsym_report(FSYM_ERR_IO, trim(path)//': need G, t_end and matching body lists', &
                             stat, errmsg)
            return
        end if
        if (any(nm(1:n0) /= nref(1:nr))) then
            call fsym_report(FSYM_ERR_IO, trim(path)//': reference bodies in another order', &
                             stat, errmsg)
            return
        end if
        dat%n = n0
        dat%name = nm(1:n0)
        dat%m = m(1:n0)
        dat%q0 = s0(1:3, 1:n0); dat%v0 = s0(4:6, 1:n0)
        dat%qref = sref(1:3, 1:n0); dat%vref = sref(4:6, 1:n0)
        stat = FSYM_SUCCESS
    end subroutine read_solar_data

end module fsym_solar_data
